#include "avar/firmware_iface/cia402_drives.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "avar/firmware_iface/can_conversation.hpp"
#include "avar/firmware_iface/canopen_sdo_client.hpp"

namespace avar::firmware_iface {
namespace {

constexpr std::chrono::milliseconds kCia402PollPause{1};

/// A device value (counts) as the INT32 a drive takes, rounded and saturated.
std::int32_t cia402_counts(double device_value) noexcept {
  const double r = std::round(device_value);
  return static_cast<std::int32_t>(std::clamp(r, -2147483648.0, 2147483647.0));
}

std::string cia402_hex(std::uint32_t value, int digits) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%0*X", digits, value);
  return text;
}

std::string cia402_millis(std::chrono::nanoseconds t) {
  return std::to_string(std::chrono::duration_cast<std::chrono::milliseconds>(t).count()) + " ms";
}

/// Lets time pass on the bus's clock, dropping what arrives meanwhile.
Status cia402_pause(FrameTransport& bus) {
  const Status s = await_frame(bus, kCia402PollPause, [](const CanFrame&) { return false; });
  return s == Status::timeout ? Status::ok : s;
}

}  // namespace

Cia402Drives::Cia402Drives(Cia402DrivesConfig config) : CanDrives(config.actuators), config_(std::move(config)) {
  for (const Cia402Actuator& a : config_.actuators) {
    if (!canopen::valid_node(a.node))
      throw std::invalid_argument("CiA 402 drive node " + std::to_string(a.node) + " is outside 1..127");
    if (find(a.node)) throw std::invalid_argument("CiA 402 drive node " + std::to_string(a.node) + " is used twice");
    drives_.push_back(new_drive(a.node));
  }
}

Cia402Drives::Drive Cia402Drives::new_drive(std::uint8_t node) const noexcept {
  Drive d;
  d.node = node;
  d.heartbeat = DeviceWatch(config_.heartbeat_budget_ticks);
  return d;
}

Cia402Drives::Drive* Cia402Drives::find(std::uint8_t node) noexcept {
  for (Drive& d : drives_)
    if (d.node == node) return &d;
  return nullptr;
}

void Cia402Drives::fail(const Drive& d, const std::string& what) {
  start_problem_ = "CiA 402 node " + std::to_string(d.node) + ": " + what;
}

// ---- start ----------------------------------------------------------------------------------------

Status Cia402Drives::start(FrameTransport& bus) {
  start_problem_.clear();
  for (std::size_t i = 0; i < drives_.size(); ++i) {
    Drive& d = drives_[i];
    if (const Status s = start_drive(bus, d); s != Status::ok) return s;
    ChannelTelemetry& t = table().telemetry(i);
    t.position = table().to_channel(i, d.target);
    t.faults = 0;
  }
  return Status::ok;
}

Status Cia402Drives::write(FrameTransport& bus, const Drive& d, std::uint16_t index, std::uint8_t sub, std::uint32_t value,
                           std::uint8_t size) {
  const canopen::SdoOutcome r = canopen::sdo_download(bus, d.node, index, sub, value, size, config_.sdo_timeout);
  if (r.status != Status::ok) fail(d, canopen::describe_sdo_failure(r, true, index, sub));
  return r.status;
}

Status Cia402Drives::read(FrameTransport& bus, const Drive& d, std::uint16_t index, std::uint8_t sub, std::uint32_t* value) {
  const canopen::SdoOutcome r = canopen::sdo_upload(bus, d.node, index, sub, config_.sdo_timeout);
  if (r.status != Status::ok) fail(d, canopen::describe_sdo_failure(r, false, index, sub));
  *value = r.value;
  return r.status;
}

Status Cia402Drives::read_state(FrameTransport& bus, Drive& d) {
  std::uint32_t sw = 0;
  if (const Status s = read(bus, d, cia402::kStatusword, 0, &sw); s != Status::ok) return s;
  d.statusword = static_cast<std::uint16_t>(sw);
  d.state = cia402::decode_state(d.statusword);
  return Status::ok;
}

Status Cia402Drives::command(FrameTransport& bus, Drive& d, std::uint16_t controlword, cia402::State want) {
  if (const Status s = write(bus, d, cia402::kControlword, 0, controlword, 2); s != Status::ok) return s;
  const auto deadline = bus.now() + config_.state_timeout;
  for (;;) {
    if (const Status s = read_state(bus, d); s != Status::ok) return s;
    if (d.state == want) return Status::ok;
    if (cia402::is_fault(d.state)) {
      fail(d, std::string("went to ") + cia402::state_name(d.state) + " after controlword " + cia402_hex(controlword, 4));
      return Status::out_of_range;
    }
    if (bus.now() >= deadline) {
      fail(d, std::string("still ") + cia402::state_name(d.state) + " " + cia402_millis(config_.state_timeout) +
                  " after controlword " + cia402_hex(controlword, 4) + " (waiting for " + cia402::state_name(want) + ")");
      return Status::timeout;
    }
    if (const Status s = cia402_pause(bus); s != Status::ok) return s;
  }
}

Status Cia402Drives::map_pdo(FrameTransport& bus, const Drive& d, std::uint16_t communication, std::uint16_t mapping,
                             std::uint32_t cob_id, std::uint32_t first, std::uint32_t second) {
  const struct {
    std::uint16_t index;
    std::uint8_t sub;
    std::uint32_t value;
    std::uint8_t size;
  } steps[] = {
      {communication, 1, canopen::kPdoInvalid | cob_id, 4},
      {mapping, 0, 0, 1},
      {mapping, 1, first, 4},
      {mapping, 2, second, 4},
      {mapping, 0, 2, 1},
      {communication, 2, 1, 1},  // synchronous, every SYNC
      {communication, 1, cob_id, 4},
  };
  for (const auto& s : steps)
    if (const Status r = write(bus, d, s.index, s.sub, s.value, s.size); r != Status::ok) return r;
  return Status::ok;
}

Status Cia402Drives::start_drive(FrameTransport& bus, Drive& d) {
  const std::uint8_t node = d.node;
  d = new_drive(node);

  // Reset communication: known PDO and heartbeat settings, and a boot-up that says the drive is there.
  const Status booted = ask_frame(bus, canopen::encode_nmt(canopen::NmtCommand::reset_communication, node), config_.boot_timeout,
                                  [&](const CanFrame& f) {
                                    std::uint8_t n = 0;
                                    canopen::NmtState st{};
                                    return canopen::decode_heartbeat(f, &n, &st) && n == node &&
                                           (st == canopen::NmtState::boot_up || st == canopen::NmtState::pre_operational);
                                  });
  if (booted != Status::ok) {
    fail(d, "no boot-up within " + cia402_millis(config_.boot_timeout) + " of NMT reset communication (" +
                std::string(to_string(booted)) + ")");
    return booted;
  }

  // Past its own initialisation and fault reaction, and out of Fault.
  const auto deadline = bus.now() + config_.state_timeout;
  for (;;) {
    if (const Status s = read_state(bus, d); s != Status::ok) return s;
    if (d.state != cia402::State::not_ready_to_switch_on && d.state != cia402::State::fault_reaction_active) break;
    if (bus.now() >= deadline) {
      fail(d,
           std::string("still ") + cia402::state_name(d.state) + " " + cia402_millis(config_.state_timeout) + " after boot-up");
      return Status::timeout;
    }
    if (const Status s = cia402_pause(bus); s != Status::ok) return s;
  }
  for (int attempt = 0; attempt < 2 && d.state == cia402::State::fault; ++attempt) {
    // The reset acts on bit 7's rising edge; the second attempt starts from 0x0000.
    if (const Status s = write(bus, d, cia402::kControlword, 0, cia402::kFaultReset, 2); s != Status::ok) return s;
    if (const Status s = write(bus, d, cia402::kControlword, 0, cia402::kDisableVoltage, 2); s != Status::ok) return s;
    if (const Status s = read_state(bus, d); s != Status::ok) return s;
  }
  if (d.state == cia402::State::fault) {
    std::uint32_t code = 0;
    const bool known = read(bus, d, cia402::kErrorCode, 0, &code) == Status::ok;
    fail(d, "stays in Fault after fault reset" + (known ? " (error code " + cia402_hex(code, 4) + ")" : std::string()));
    return Status::out_of_range;
  }

  // Cyclic synchronous position, confirmed by the drive.
  constexpr auto kCsp = static_cast<std::uint8_t>(cia402::Mode::cyclic_synchronous_position);
  if (const Status s = write(bus, d, cia402::kModesOfOperation, 0, kCsp, 1); s != Status::ok) return s;
  const auto mode_deadline = bus.now() + config_.state_timeout;
  for (;;) {
    std::uint32_t shown = 0;
    if (const Status s = read(bus, d, cia402::kModesOfOperationDisplay, 0, &shown); s != Status::ok) return s;
    if (shown == kCsp) break;
    if (bus.now() >= mode_deadline) {
      const auto mode = static_cast<std::int8_t>(shown);
      fail(d, "0x6061 shows mode " + std::to_string(mode) + " (" + cia402::mode_name(mode) +
                  "), not 8 (cyclic synchronous position)");
      return Status::timeout;
    }
    if (const Status s = cia402_pause(bus); s != Status::ok) return s;
  }

  if (const Status s = write(bus, d, canopen::kHeartbeatProducerTime, 0, config_.heartbeat_ms, 2); s != Status::ok) return s;
  if (const Status s = map_pdo(bus, d, canopen::kRpdoCommunication, canopen::kRpdoMapping, canopen::rpdo_cob_id(1, node),
                               canopen::pdo_mapping_entry(cia402::kControlword, 0, 16),
                               canopen::pdo_mapping_entry(cia402::kTargetPosition, 0, 32));
      s != Status::ok)
    return s;
  if (const Status s = map_pdo(bus, d, canopen::kTpdoCommunication, canopen::kTpdoMapping, canopen::tpdo_cob_id(1, node),
                               canopen::pdo_mapping_entry(cia402::kStatusword, 0, 16),
                               canopen::pdo_mapping_entry(cia402::kPositionActual, 0, 32));
      s != Status::ok)
    return s;

  // Hold where it is: the target becomes the present position before anything is enabled.
  std::uint32_t actual = 0;
  if (const Status s = read(bus, d, cia402::kPositionActual, 0, &actual); s != Status::ok) return s;
  d.target = static_cast<std::int32_t>(actual);
  if (const Status s = write(bus, d, cia402::kTargetPosition, 0, actual, 4); s != Status::ok) return s;

  const CanFrame start = canopen::encode_nmt(canopen::NmtCommand::start, node);
  if (const Status s = bus.send(std::span<const CanFrame>(&start, 1)); s != Status::ok) {
    fail(d, "NMT start not sent (" + std::string(to_string(s)) + ")");
    return s;
  }
  if (config_.heartbeat_ms > 0) {
    const auto wait =
        std::max<std::chrono::nanoseconds>(config_.state_timeout, 3 * std::chrono::milliseconds(config_.heartbeat_ms));
    const Status s = await_frame(bus, wait, [&](const CanFrame& f) {
      std::uint8_t n = 0;
      canopen::NmtState st{};
      return canopen::decode_heartbeat(f, &n, &st) && n == node && st == canopen::NmtState::operational;
    });
    if (s != Status::ok) {
      fail(d, "no Operational heartbeat within " + cia402_millis(wait) + " of NMT start (" + std::string(to_string(s)) + ")");
      return s;
    }
  }
  d.nmt = canopen::NmtState::operational;

  if (const Status s = command(bus, d, cia402::kShutdown, cia402::State::ready_to_switch_on); s != Status::ok) return s;
  if (const Status s = command(bus, d, cia402::kSwitchOn, cia402::State::switched_on); s != Status::ok) return s;
  return command(bus, d, cia402::kEnableOperation, cia402::State::operation_enabled);
}

Status Cia402Drives::read_positions(FrameTransport& bus, std::span<double> frame, std::span<bool> known) {
  Status result = Status::ok;
  for (std::size_t i = 0; i < drives_.size(); ++i) {
    const canopen::SdoOutcome r = canopen::sdo_upload(bus, drives_[i].node, cia402::kPositionActual, 0, config_.sdo_timeout);
    if (r.status != Status::ok) {
      if (result == Status::ok) result = r.status;
      continue;
    }
    frame[table().channel(i)] = table().to_channel(i, static_cast<std::int32_t>(r.value));
    known[table().channel(i)] = true;
  }
  return result;
}

// ---- the tick ---------------------------------------------------------------------------------------

void Cia402Drives::encode_tick(std::span<const double> frame, CanOutbox& out) noexcept {
  for (std::size_t i = 0; i < drives_.size(); ++i) {
    Drive& d = drives_[i];
    d.tpdo_seen = false;
    const std::uint32_t rpdo = canopen::rpdo_cob_id(1, d.node);
    if (table().released(i)) {
      d.driven = false;
      if (table().release_pending(i) && out.push(cia402::encode_control_target(rpdo, cia402::kDisableVoltage, d.target)))
        table().set_release_told(i);
      continue;
    }
    d.driven = true;
    d.target = cia402_counts(table().to_device(i, frame));
    out.push(cia402::encode_control_target(rpdo, cia402::kEnableOperation, d.target));
  }
  out.push(canopen::encode_sync());
}

bool Cia402Drives::take(const CanFrame& frame) noexcept {
  if (frame.extended || frame.rtr || frame.error) return false;
  const canopen::CobId cob = canopen::decode_cob_id(frame.id);
  Drive* d = find(cob.node);
  if (!d) return false;
  const auto i = static_cast<std::size_t>(d - drives_.data());
  switch (cob.function) {
    case canopen::CobFunction::tpdo1: {
      std::int32_t position = 0;
      if (!cia402::decode_status_position(frame, frame.id, &d->statusword, &position)) return false;
      d->state = cia402::decode_state(d->statusword);
      d->state_fault = cia402::is_fault(d->state) || (d->driven && d->state != cia402::State::operation_enabled);
      d->tpdo_seen = true;
      ChannelTelemetry& t = table().telemetry(i);
      t.position = table().to_channel(i, position);
      t.faults = faults_of(*d);
      ++t.updates;
      return true;
    }
    case canopen::CobFunction::heartbeat: {
      std::uint8_t node = 0;
      if (!canopen::decode_heartbeat(frame, &node, &d->nmt)) return false;
      d->heartbeat_seen = true;
      d->nmt_fault = d->driven && d->nmt != canopen::NmtState::operational;
      table().telemetry(i).faults = faults_of(*d);
      return true;
    }
    case canopen::CobFunction::emcy: {
      std::uint8_t node = 0;
      canopen::Emcy emcy;
      if (!canopen::decode_emcy(frame, &node, &emcy)) return false;
      if (emcy.error_code != 0) {
        d->emcy_code = emcy.error_code;
        device_errors_.fetch_add(1, std::memory_order_relaxed);
      }
      return true;
    }
    default: return false;
  }
}

bool Cia402Drives::replies_complete() const noexcept {
  return std::all_of(drives_.begin(), drives_.end(), [](const Drive& d) { return d.tpdo_seen || d.tpdos.lost(); });
}

Status Cia402Drives::settle() noexcept {
  bool complete = true;
  for (std::size_t i = 0; i < drives_.size(); ++i) {
    Drive& d = drives_[i];
    if (d.tpdo_seen) {
      d.tpdos.answered();
    } else {
      d.tpdos.missed();
      table().forget_feedback(i);
      complete = false;
    }
    if (d.heartbeat_seen) d.heartbeat.answered();
    else d.heartbeat.missed();
    d.heartbeat_seen = false;
    d.lost = watch_heartbeats() && d.heartbeat.lost();
    table().telemetry(i).faults = faults_of(d);
  }
  return complete ? Status::ok : Status::timeout;
}

void Cia402Drives::encode_release(CanOutbox& out) noexcept {
  for (const Drive& d : drives_)
    out.push(cia402::encode_control_target(canopen::rpdo_cob_id(1, d.node), cia402::kDisableVoltage, d.target));
  out.push(canopen::encode_sync());
  table().release_all_told();
}

std::uint32_t Cia402Drives::faults_of(const Drive& d) const noexcept {
  std::uint32_t f = 0;
  if (d.state_fault || d.nmt_fault) f |= kDeviceFaultState;
  if (cia402::is_fault(d.state)) f |= cia402::emcy_device_faults(d.emcy_code);
  if (d.lost) f |= kDeviceLost;
  return f;
}

std::string Cia402Drives::channel_problem(std::size_t channel) const {
  for (std::size_t i = 0; i < drives_.size(); ++i) {
    if (table().channel(i) != channel) continue;
    const Drive& d = drives_[i];
    const std::string who = "CiA 402 node " + std::to_string(d.node) + ": ";
    const std::string emcy = d.emcy_code ? " (EMCY " + cia402_hex(d.emcy_code, 4) + ")" : std::string();
    if (d.lost) return who + "no heartbeat for " + std::to_string(d.heartbeat.silent_ticks()) + " ticks";
    if (cia402::is_fault(d.state)) return who + cia402::state_name(d.state) + emcy;
    if (d.state_fault) return who + "left Operation enabled for " + cia402::state_name(d.state) + emcy;
    if (d.nmt_fault) return who + "NMT " + canopen::nmt_state_name(d.nmt) + ", not Operational";
    if (d.emcy_code) return who + "EMCY " + cia402_hex(d.emcy_code, 4);
  }
  return {};
}

}  // namespace avar::firmware_iface
