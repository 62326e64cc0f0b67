#include "avar/sim/sim_cia402_drive.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "avar/core/byte_order.hpp"

namespace avar::sim {
namespace canopen = firmware_iface::canopen;
namespace cia402 = firmware_iface::cia402;
using Cia402State = firmware_iface::cia402::State;
using firmware_iface::CanFrame;
namespace {

constexpr std::uint8_t kCia402MaxMapped = 8;
constexpr std::uint32_t kCia402CobIdMask = 0x7FF;
constexpr std::uint32_t kCia402CobIdExtended = 1u << 29;
constexpr std::uint16_t kCia402EmcyPdoLength = 0x8210;  // PDO not processed: length error

bool cia402_voltage_enabled(Cia402State s) {
  return s == Cia402State::ready_to_switch_on || s == Cia402State::switched_on || s == Cia402State::operation_enabled ||
         s == Cia402State::quick_stop_active || s == Cia402State::fault_reaction_active;
}

/// 0x1001 bits for an EMCY code's class: generic always, current / voltage / temperature /
/// communication / device profile where the class says so.
std::uint8_t cia402_error_register_for(std::uint16_t code) {
  std::uint8_t r = 0x01;
  switch (code >> 12) {
    case 0x2: r |= 0x02; break;
    case 0x3: r |= 0x04; break;
    case 0x4: r |= 0x08; break;
    case 0x8: r |= 0x10; break;
    case 0x7: r |= 0x20; break;
    default: break;
  }
  return r;
}

}  // namespace

SimCia402Drive::SimCia402Drive(SimCia402DriveConfig config) : config_(config) {
  if (!canopen::valid_node(config_.node)) throw std::invalid_argument("SimCia402Drive: node must be 1..127");
  if (!(config_.counts_per_turn > 0)) throw std::invalid_argument("SimCia402Drive: counts_per_turn must be > 0");
  config_.motor.encoder_counts_per_turn = config_.counts_per_turn;
  motor_ = CanMotorModel(config_.motor, config_.initial_position * 2 * std::numbers::pi / config_.counts_per_turn);
  build_dictionary();
  reset_application();
  reset_communication();
}

void SimCia402Drive::build_dictionary() {
  using A = ObjectAccess;
  using M = PdoMappable;
  const auto add = [&](std::uint16_t index, std::uint8_t sub, std::uint8_t size, bool is_signed, A access, M mappable,
                       std::uint32_t raw = 0) {
    od_.add({index, sub, size, is_signed, access, mappable, false, 0, 0, raw});
  };
  const auto add_ranged = [&](std::uint16_t index, std::uint8_t sub, std::uint8_t size, bool is_signed, A access, M mappable,
                              std::int64_t min, std::int64_t max, std::uint32_t raw = 0) {
    od_.add({index, sub, size, is_signed, access, mappable, true, min, max, raw});
  };
  add(canopen::kDeviceType, 0, 4, false, A::read_only, M::no, 0x00020192);  // CiA 402, servo drive
  add(canopen::kErrorRegister, 0, 1, false, A::read_only, M::tpdo);
  add(canopen::kHeartbeatProducerTime, 0, 2, false, A::read_write, M::no);
  for (std::uint16_t k = 0; k < kPdos; ++k) {
    for (const std::uint16_t comm : {static_cast<std::uint16_t>(canopen::kRpdoCommunication + k),
                                     static_cast<std::uint16_t>(canopen::kTpdoCommunication + k)}) {
      add(comm, 0, 1, false, A::read_only, M::no, 2);  // highest sub-index
      add(comm, 1, 4, false, A::read_write, M::no);    // COB-ID
      add(comm, 2, 1, false, A::read_write, M::no);    // transmission type
    }
    for (const std::uint16_t map :
         {static_cast<std::uint16_t>(canopen::kRpdoMapping + k), static_cast<std::uint16_t>(canopen::kTpdoMapping + k)}) {
      add_ranged(map, 0, 1, false, A::read_write, M::no, 0, kCia402MaxMapped);
      for (std::uint8_t s = 1; s <= kCia402MaxMapped; ++s) add(map, s, 4, false, A::read_write, M::no);
    }
  }
  add(cia402::kErrorCode, 0, 2, false, A::read_only, M::tpdo);
  add(cia402::kControlword, 0, 2, false, A::read_write, M::rpdo);
  add(cia402::kStatusword, 0, 2, false, A::read_only, M::tpdo);
  add(cia402::kModesOfOperation, 0, 1, true, A::read_write, M::rpdo);
  add(cia402::kModesOfOperationDisplay, 0, 1, true, A::read_only, M::tpdo);
  add(cia402::kPositionActual, 0, 4, true, A::read_only, M::tpdo);
  add(cia402::kTargetPosition, 0, 4, true, A::read_write, M::rpdo);
  add(cia402::kSoftwarePositionLimit, 0, 1, false, A::read_only, M::no, 2);
  add(cia402::kSoftwarePositionLimit, 1, 4, true, A::read_write, M::no, static_cast<std::uint32_t>(config_.position_min));
  add(cia402::kSoftwarePositionLimit, 2, 4, true, A::read_write, M::no, static_cast<std::uint32_t>(config_.position_max));
  add(cia402::kSupportedDriveModes, 0, 4, false, A::read_only, M::no, config_.supported_modes);
}

void SimCia402Drive::reset_application() {
  od_.set(cia402::kControlword, 0, 0);
  od_.set(cia402::kModesOfOperation, 0, 0);
  od_.set(cia402::kModesOfOperationDisplay, 0, 0);
  od_.set(cia402::kTargetPosition, 0, 0);
  od_.set(cia402::kErrorCode, 0, 0);
  od_.set(canopen::kErrorRegister, 0, 0);
  state_ = Cia402State::not_ready_to_switch_on;
  last_transition_ = 0;
  state_timer_s_ = config_.init_s;
  feedforward_rad_s_ = 0;
  refresh();
}

void SimCia402Drive::reset_communication() {
  const std::uint8_t node = config_.node;
  od_.set(canopen::kHeartbeatProducerTime, 0, config_.heartbeat_ms);
  for (std::uint16_t k = 0; k < kPdos; ++k) {
    const auto rpdo_comm = static_cast<std::uint16_t>(canopen::kRpdoCommunication + k);
    const auto tpdo_comm = static_cast<std::uint16_t>(canopen::kTpdoCommunication + k);
    const auto rpdo_map = static_cast<std::uint16_t>(canopen::kRpdoMapping + k);
    const auto tpdo_map = static_cast<std::uint16_t>(canopen::kTpdoMapping + k);
    // Vendor default: PDO 1 valid and event-driven, controlword in / statusword out; others off.
    od_.set(rpdo_comm, 1, canopen::rpdo_cob_id(k + 1, node) | (k == 0 ? 0 : canopen::kPdoInvalid));
    od_.set(rpdo_comm, 2, canopen::kPdoEventProfile);
    od_.set(tpdo_comm, 1, canopen::tpdo_cob_id(k + 1, node) | (k == 0 ? 0 : canopen::kPdoInvalid));
    od_.set(tpdo_comm, 2, canopen::kPdoEventProfile);
    for (std::uint8_t s = 0; s <= kCia402MaxMapped; ++s) {
      od_.set(rpdo_map, s, 0);
      od_.set(tpdo_map, s, 0);
    }
    if (k == 0) {
      od_.set(rpdo_map, 0, 1);
      od_.set(rpdo_map, 1, canopen::pdo_mapping_entry(cia402::kControlword, 0, 16));
      od_.set(tpdo_map, 0, 1);
      od_.set(tpdo_map, 1, canopen::pdo_mapping_entry(cia402::kStatusword, 0, 16));
    }
  }
  rpdos_ = {};
  tpdos_ = {};
  tx_.clear();
  heartbeat_timer_s_ = 0;
  nmt_ = canopen::NmtState::pre_operational;
  send(canopen::encode_heartbeat(node, canopen::NmtState::boot_up));
}

double SimCia402Drive::position_counts() const noexcept {
  return motor_.position() * config_.counts_per_turn / (2 * std::numbers::pi);
}

std::uint16_t SimCia402Drive::statusword() const noexcept {
  std::uint16_t sw = cia402::state_bits(state_) | cia402::kSwRemote;
  if (cia402_voltage_enabled(state_)) sw |= cia402::kSwVoltageEnabled;
  if (state_ == Cia402State::operation_enabled && od_.value(cia402::kModesOfOperationDisplay, 0) == 8)
    sw |= cia402::kSwSetPointAcknowledge;
  return sw;
}

void SimCia402Drive::refresh() {
  od_.set(cia402::kStatusword, 0, statusword());
  const double counts = motor_.measured_position() * config_.counts_per_turn / (2 * std::numbers::pi);
  od_.set(cia402::kPositionActual, 0, static_cast<std::uint32_t>(static_cast<std::int32_t>(std::lround(counts))));
}

// ---- frames in and out --------------------------------------------------------------------------

void SimCia402Drive::receive(const CanFrame& frame) {
  if (frame.extended || frame.rtr || frame.error) return;
  canopen::NmtCommand command{};
  std::uint8_t node = 0;
  if (canopen::decode_nmt(frame, &command, &node)) {
    if (node == 0 || node == config_.node) on_nmt(command);
    send_event_tpdos();
    return;
  }
  if (nmt_ == canopen::NmtState::stopped) return;  // Stopped: NMT and heartbeat only
  if (canopen::is_sync(frame)) {
    if (nmt_ == canopen::NmtState::operational) on_sync();
    return;
  }
  if (frame.id == canopen::sdo_request_cob_id(config_.node)) {
    bool from_server = false;
    canopen::Sdo sdo;
    if (canopen::decode_sdo(frame, &node, &from_server, &sdo)) on_sdo(sdo);
    send_event_tpdos();
    return;
  }
  if (nmt_ != canopen::NmtState::operational) return;
  for (int k = 0; k < kPdos; ++k) {
    const auto comm = static_cast<std::uint16_t>(canopen::kRpdoCommunication + k);
    if (pdo_valid(comm) && frame.id == (od_.get(comm, 1) & kCia402CobIdMask)) {
      on_rpdo(k, frame);
      send_event_tpdos();
      return;
    }
  }
}

bool SimCia402Drive::peek_transmit(CanFrame* frame) const {
  if (tx_.empty()) return false;
  *frame = tx_.front();
  return true;
}

void SimCia402Drive::pop_transmit() {
  if (!tx_.empty()) tx_.pop_front();
}

void SimCia402Drive::send_emcy(std::uint16_t code, std::uint8_t error_register) {
  if (nmt_ == canopen::NmtState::stopped) return;
  canopen::Emcy emcy;
  emcy.error_code = code;
  emcy.error_register = error_register;
  send(canopen::encode_emcy(config_.node, emcy));
}

// ---- NMT ------------------------------------------------------------------------------------------

void SimCia402Drive::on_nmt(canopen::NmtCommand command) {
  switch (command) {
    case canopen::NmtCommand::start: nmt_ = canopen::NmtState::operational; break;
    case canopen::NmtCommand::stop: nmt_ = canopen::NmtState::stopped; break;
    case canopen::NmtCommand::enter_pre_operational: nmt_ = canopen::NmtState::pre_operational; break;
    case canopen::NmtCommand::reset_node:
      reset_application();
      reset_communication();
      break;
    case canopen::NmtCommand::reset_communication: reset_communication(); break;
  }
}

// ---- SDO server -----------------------------------------------------------------------------------

void SimCia402Drive::sdo_abort(std::uint16_t index, std::uint8_t sub, std::uint32_t code) {
  ++sdo_aborts_;
  send(canopen::encode_sdo_abort(config_.node, true, index, sub, code));
}

void SimCia402Drive::on_sdo(const canopen::Sdo& sdo) {
  switch (sdo.kind) {
    case canopen::SdoKind::upload_request: {
      const ObjectEntry* entry = nullptr;
      if (const std::uint32_t abort = od_.check_read(sdo.index, sdo.sub, &entry)) return sdo_abort(sdo.index, sdo.sub, abort);
      send(canopen::encode_sdo_upload_response(config_.node, sdo.index, sdo.sub, entry->raw, entry->size));
      return;
    }
    case canopen::SdoKind::download_request: {
      // Only expedited transfers: a segmented one is refused at its start.
      if (!sdo.expedited) return sdo_abort(sdo.index, sdo.sub, canopen::kSdoAbortUnsupportedAccess);
      ObjectEntry* entry = nullptr;
      std::uint32_t raw = 0;
      std::uint32_t abort = od_.check_write(sdo.index, sdo.sub, sdo.data, sdo.size, &entry, &raw);
      if (!abort) abort = validate(*entry, raw);
      if (abort) return sdo_abort(sdo.index, sdo.sub, abort);
      apply(*entry, raw);
      send(canopen::encode_sdo_download_response(config_.node, sdo.index, sdo.sub));
      return;
    }
    case canopen::SdoKind::abort: return;  // the client gave up; nothing is in progress
    case canopen::SdoKind::download_response:
    case canopen::SdoKind::upload_response:
    case canopen::SdoKind::other: return sdo_abort(sdo.index, sdo.sub, canopen::kSdoAbortInvalidCommand);
  }
}

bool SimCia402Drive::pdo_valid(std::uint16_t communication_index) const {
  return !(od_.get(communication_index, 1) & canopen::kPdoInvalid);
}

std::uint32_t SimCia402Drive::validate(const ObjectEntry& e, std::uint32_t raw) const {
  const std::uint16_t index = e.index;
  if (index == cia402::kModesOfOperation) {
    const auto mode = static_cast<std::int8_t>(raw);
    if (!(config_.supported_modes & cia402::supported_mode_bit(mode))) return canopen::kSdoAbortValueRange;
    return 0;
  }
  if (index == cia402::kTargetPosition) {
    const auto target = static_cast<std::int32_t>(raw);
    if (target > od_.value(cia402::kSoftwarePositionLimit, 2)) return canopen::kSdoAbortValueTooHigh;
    if (target < od_.value(cia402::kSoftwarePositionLimit, 1)) return canopen::kSdoAbortValueTooLow;
    return 0;
  }
  const bool rpdo_comm = index >= canopen::kRpdoCommunication && index < canopen::kRpdoCommunication + kPdos;
  const bool tpdo_comm = index >= canopen::kTpdoCommunication && index < canopen::kTpdoCommunication + kPdos;
  if (rpdo_comm || tpdo_comm) {
    if (e.sub == 1) {
      // A valid PDO's identifier cannot change; a new one must be a standard identifier.
      const bool valid_now = !(e.raw & canopen::kPdoInvalid);
      const bool valid_next = !(raw & canopen::kPdoInvalid);
      if (raw & kCia402CobIdExtended) return canopen::kSdoAbortValueRange;
      if (valid_now && valid_next && (raw & kCia402CobIdMask) != (e.raw & kCia402CobIdMask)) return canopen::kSdoAbortValueRange;
      if (valid_next && (raw & kCia402CobIdMask) == 0) return canopen::kSdoAbortValueRange;
    } else if (e.sub == 2) {
      const std::uint32_t type = raw;
      if (rpdo_comm && type > canopen::kPdoSyncMaxCycle && type < canopen::kPdoEventManufacturer)
        return canopen::kSdoAbortValueRange;
      if (tpdo_comm && type > canopen::kPdoSyncMaxCycle && type < canopen::kPdoRtrSync) return canopen::kSdoAbortValueRange;
    }
    return 0;
  }
  const bool rpdo_map = index >= canopen::kRpdoMapping && index < canopen::kRpdoMapping + kPdos;
  const bool tpdo_map = index >= canopen::kTpdoMapping && index < canopen::kTpdoMapping + kPdos;
  if (rpdo_map || tpdo_map) {
    const auto comm = static_cast<std::uint16_t>(index - canopen::kRpdoMapping + canopen::kRpdoCommunication);
    // The mapping changes only while the PDO is invalid; entries only while the count is 0.
    if (pdo_valid(comm)) return canopen::kSdoAbortDeviceState;
    if (e.sub == 0) {
      int bits = 0;
      for (std::uint32_t s = 1; s <= raw; ++s) {  // raw <= kCia402MaxMapped: the entry's range
        const std::uint32_t entry = od_.get(index, static_cast<std::uint8_t>(s));
        if (entry == 0) return canopen::kSdoAbortValueRange;  // counting an entry never written
        bits += canopen::decode_pdo_mapping(entry).bits;
      }
      if (bits > 64) return canopen::kSdoAbortPdoTooLong;
      return 0;
    }
    if (od_.get(index, 0) != 0) return canopen::kSdoAbortDeviceState;
    if (raw == 0) return 0;
    const canopen::PdoMapping m = canopen::decode_pdo_mapping(raw);
    if (!od_.can_map(m.index, m.sub, m.bits, rpdo_map)) return canopen::kSdoAbortCannotMap;
    return 0;
  }
  return 0;
}

void SimCia402Drive::apply(ObjectEntry& e, std::uint32_t raw) {
  const std::uint32_t previous = e.raw;
  e.raw = raw;
  if (e.index == cia402::kControlword) {
    on_controlword(static_cast<std::uint16_t>(raw), static_cast<std::uint16_t>(previous));
  } else if (e.index == cia402::kTargetPosition) {
    on_target(static_cast<std::int32_t>(raw), static_cast<std::int32_t>(previous));
  } else if (e.index == canopen::kHeartbeatProducerTime) {
    heartbeat_timer_s_ = 0;
  } else if (e.index >= canopen::kTpdoCommunication && e.index < canopen::kTpdoCommunication + kPdos) {
    tpdos_[e.index - canopen::kTpdoCommunication] = {};
  }
  refresh();
}

// ---- CiA 402 --------------------------------------------------------------------------------------

void SimCia402Drive::on_controlword(std::uint16_t cw, std::uint16_t previous) {
  // Switch on + enable operation from Ready to switch on takes transitions 3 then 4.
  for (int step = 0; step < 3; ++step) {
    const cia402::Transition t = cia402::next_state(state_, cw, previous);
    if (t.number == 0) return;
    enter(t.to, t.number);
    previous = cw;
  }
}

void SimCia402Drive::on_target(std::int32_t target, std::int32_t previous) {
  // The target's velocity (its last step over the time it took), fed forward to the position
  // loop until the next target is overdue.
  const double dt = time_s_ - target_time_s_;
  target_time_s_ = time_s_;
  if (dt > 0 && dt < 0.1) {
    feedforward_rad_s_ = static_cast<double>(target - previous) * 2 * std::numbers::pi / config_.counts_per_turn / dt;
    feedforward_until_s_ = time_s_ + 1.5 * dt;
  } else {
    feedforward_rad_s_ = 0;
  }
}

void SimCia402Drive::enter(Cia402State to, int transition) {
  const Cia402State from = state_;
  state_ = to;
  last_transition_ = transition;
  if (to == Cia402State::quick_stop_active || to == Cia402State::fault_reaction_active ||
      (to == Cia402State::operation_enabled && from != Cia402State::operation_enabled))
    hold_rad_ = motor_.position();
  if (to == Cia402State::fault_reaction_active) state_timer_s_ = config_.fault_reaction_s;
  if (transition == 15) {
    od_.set(cia402::kErrorCode, 0, 0);
    od_.set(canopen::kErrorRegister, 0, 0);
    send_emcy(0x0000, 0);  // error reset
  }
  refresh();
}

void SimCia402Drive::raise_fault(std::uint16_t emcy_code) {
  const std::uint8_t reg = cia402_error_register_for(emcy_code);
  od_.set(cia402::kErrorCode, 0, emcy_code);
  od_.set(canopen::kErrorRegister, 0, reg);
  send_emcy(emcy_code, reg);
  if (state_ != Cia402State::fault && state_ != Cia402State::fault_reaction_active) enter(Cia402State::fault_reaction_active, 13);
}

// ---- PDOs -----------------------------------------------------------------------------------------

int SimCia402Drive::pdo_bytes(std::uint16_t mapping_index) const {
  int bits = 0;
  const auto count = static_cast<std::uint8_t>(od_.get(mapping_index, 0));
  for (std::uint8_t s = 1; s <= count; ++s) bits += canopen::decode_pdo_mapping(od_.get(mapping_index, s)).bits;
  return (bits + 7) / 8;
}

void SimCia402Drive::on_rpdo(int k, const CanFrame& frame) {
  const auto map = static_cast<std::uint16_t>(canopen::kRpdoMapping + k);
  if (frame.dlc < pdo_bytes(map)) {
    send_emcy(kCia402EmcyPdoLength, static_cast<std::uint8_t>(od_.get(canopen::kErrorRegister, 0) | 0x10));
    return;
  }
  Pdo& pdo = rpdos_[static_cast<std::size_t>(k)];
  pdo.pending = frame.data;
  pdo.has_pending = true;
  const auto type = od_.get(static_cast<std::uint16_t>(canopen::kRpdoCommunication + k), 2);
  if (type >= canopen::kPdoEventManufacturer) apply_rpdo(k);
}

void SimCia402Drive::apply_rpdo(int k) {
  Pdo& pdo = rpdos_[static_cast<std::size_t>(k)];
  pdo.has_pending = false;
  const auto map = static_cast<std::uint16_t>(canopen::kRpdoMapping + k);
  const auto count = static_cast<std::uint8_t>(od_.get(map, 0));
  std::size_t at = 0;
  for (std::uint8_t s = 1; s <= count; ++s) {
    const canopen::PdoMapping m = canopen::decode_pdo_mapping(od_.get(map, s));
    const std::size_t bytes = m.bits / 8u;
    ObjectEntry* e = od_.find(m.index, m.sub);
    if (e) {
      std::uint32_t raw = get_le(&pdo.pending[at], bytes);
      if (m.index == cia402::kTargetPosition) {
        // Software position limits clamp a PDO target (an SDO write beyond them is refused).
        const std::int64_t t =
            std::clamp<std::int64_t>(static_cast<std::int32_t>(raw), od_.value(cia402::kSoftwarePositionLimit, 1),
                                     od_.value(cia402::kSoftwarePositionLimit, 2));
        raw = static_cast<std::uint32_t>(static_cast<std::int32_t>(t));
      }
      apply(*e, raw);
    }
    at += bytes;
  }
}

CanFrame SimCia402Drive::tpdo_frame(int k) const {
  const auto map = static_cast<std::uint16_t>(canopen::kTpdoMapping + k);
  CanFrame f;
  f.id = od_.get(static_cast<std::uint16_t>(canopen::kTpdoCommunication + k), 1) & kCia402CobIdMask;
  const auto count = static_cast<std::uint8_t>(od_.get(map, 0));
  std::size_t at = 0;
  for (std::uint8_t s = 1; s <= count; ++s) {
    const canopen::PdoMapping m = canopen::decode_pdo_mapping(od_.get(map, s));
    const std::size_t bytes = m.bits / 8u;
    put_le(&f.data[at], od_.get(m.index, m.sub), bytes);
    at += bytes;
  }
  f.dlc = static_cast<std::uint8_t>(at);
  return f;
}

void SimCia402Drive::send_tpdo(int k) {
  const CanFrame f = tpdo_frame(k);
  Pdo& pdo = tpdos_[static_cast<std::size_t>(k)];
  pdo.last = f.data;
  pdo.sent = true;
  send(f);
}

void SimCia402Drive::on_sync() {
  ++syncs_;
  for (int k = 0; k < kPdos; ++k) {
    const auto comm = static_cast<std::uint16_t>(canopen::kRpdoCommunication + k);
    if (rpdos_[static_cast<std::size_t>(k)].has_pending && pdo_valid(comm) && od_.get(comm, 2) <= canopen::kPdoSyncMaxCycle)
      apply_rpdo(k);
  }
  for (int k = 0; k < kPdos; ++k) {
    const auto comm = static_cast<std::uint16_t>(canopen::kTpdoCommunication + k);
    if (!pdo_valid(comm)) continue;
    const std::uint32_t type = od_.get(comm, 2);
    Pdo& pdo = tpdos_[static_cast<std::size_t>(k)];
    if (type == canopen::kPdoSyncAcyclic) {
      if (!pdo.sent || tpdo_frame(k).data != pdo.last) send_tpdo(k);
    } else if (type <= canopen::kPdoSyncMaxCycle && ++pdo.syncs >= type) {
      pdo.syncs = 0;
      send_tpdo(k);
    }
  }
}

void SimCia402Drive::send_event_tpdos() {
  if (nmt_ != canopen::NmtState::operational) return;
  for (int k = 0; k < kPdos; ++k) {
    const auto comm = static_cast<std::uint16_t>(canopen::kTpdoCommunication + k);
    if (!pdo_valid(comm) || od_.get(comm, 2) < canopen::kPdoEventManufacturer) continue;
    const Pdo& pdo = tpdos_[static_cast<std::size_t>(k)];
    if (!pdo.sent || tpdo_frame(k).data != pdo.last) send_tpdo(k);
  }
}

// ---- time -----------------------------------------------------------------------------------------

void SimCia402Drive::advance(double dt_s) {
  if (dt_s <= 0) return;
  time_s_ += dt_s;
  if (state_ == Cia402State::not_ready_to_switch_on || state_ == Cia402State::fault_reaction_active) {
    state_timer_s_ -= dt_s;
    if (state_timer_s_ <= 0) {
      if (state_ == Cia402State::not_ready_to_switch_on) enter(Cia402State::switch_on_disabled, 1);
      else enter(Cia402State::fault, 14);
    }
  }
  od_.set(cia402::kModesOfOperationDisplay, 0, od_.get(cia402::kModesOfOperation, 0));

  MotorCommand command;
  command.kp = config_.kp;
  command.kd = motor_.critical_kd(config_.kp);
  const bool csp = od_.value(cia402::kModesOfOperationDisplay, 0) == static_cast<int>(cia402::Mode::cyclic_synchronous_position);
  if (state_ == Cia402State::operation_enabled && csp) {
    command.enabled = true;
    command.position =
        static_cast<double>(od_.value(cia402::kTargetPosition, 0)) * 2 * std::numbers::pi / config_.counts_per_turn;
    command.velocity = time_s_ <= feedforward_until_s_ ? feedforward_rad_s_ : 0;
  } else if (state_ == Cia402State::operation_enabled || state_ == Cia402State::quick_stop_active ||
             state_ == Cia402State::fault_reaction_active) {
    command.enabled = true;
    command.position = hold_rad_;
  }
  motor_.advance(dt_s, command);
  refresh();

  const double period_s = static_cast<double>(od_.get(canopen::kHeartbeatProducerTime, 0)) / 1000.0;
  if (period_s > 0) {
    heartbeat_timer_s_ += dt_s;
    if (heartbeat_timer_s_ + 1e-9 >= period_s) {
      heartbeat_timer_s_ = std::fmod(heartbeat_timer_s_ + 1e-9, period_s);
      if (!heartbeat_silent_) send(canopen::encode_heartbeat(config_.node, nmt_));
    }
  }
  send_event_tpdos();
}

}  // namespace avar::sim
