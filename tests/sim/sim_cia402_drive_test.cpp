// The simulated CiA 402 drive on its own: NMT and heartbeat, the SDO server and its aborts, PDO
// mapping through SDO, SYNC, every transition of the power state machine, CSP motion, faults.
#include "avar/sim/sim_cia402_drive.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace avar::sim {
namespace {

namespace canopen = firmware_iface::canopen;
namespace cia402 = firmware_iface::cia402;
using Cia402State = firmware_iface::cia402::State;
using firmware_iface::CanFrame;

/// A drive and what it sent, driven frame by frame.
struct Cia402SimBench {
  explicit Cia402SimBench(SimCia402DriveConfig config = {}) : drive(config), node(config.node) { collect(); }

  void collect() {
    CanFrame f;
    while (drive.peek_transmit(&f)) {
      out.push_back(f);
      drive.pop_transmit();
    }
  }
  void put(const CanFrame& f) {
    drive.receive(f);
    collect();
  }
  void wait(double seconds, double step = 0.001) {
    for (double t = 0; t < seconds - 1e-12; t += step) {
      drive.advance(step);
      collect();
    }
  }
  /// The last SDO response sent, or an empty frame.
  CanFrame last_sdo() const {
    for (auto it = out.rbegin(); it != out.rend(); ++it)
      if (it->id == canopen::sdo_response_cob_id(node)) return *it;
    return {};
  }
  canopen::Sdo answer() const {
    canopen::Sdo sdo;
    std::uint8_t n = 0;
    bool from_server = false;
    EXPECT_TRUE(canopen::decode_sdo(last_sdo(), &n, &from_server, &sdo));
    EXPECT_TRUE(from_server);
    EXPECT_EQ(n, node);
    return sdo;
  }
  /// SDO write; 0 when confirmed, else the abort code.
  std::uint32_t write(std::uint16_t index, std::uint8_t sub, std::uint32_t value, std::uint8_t size) {
    out.clear();
    put(canopen::encode_sdo_download(node, index, sub, value, size));
    const canopen::Sdo sdo = answer();
    EXPECT_EQ(sdo.index, index);
    EXPECT_EQ(sdo.sub, sub);
    if (sdo.kind == canopen::SdoKind::abort) return sdo.data;
    EXPECT_EQ(sdo.kind, canopen::SdoKind::download_response);
    return 0;
  }
  /// SDO read: the value, or the abort code in *abort.
  std::uint32_t read(std::uint16_t index, std::uint8_t sub, std::uint32_t* abort = nullptr, std::uint8_t* size = nullptr) {
    out.clear();
    put(canopen::encode_sdo_upload(node, index, sub));
    const canopen::Sdo sdo = answer();
    if (abort) *abort = sdo.kind == canopen::SdoKind::abort ? sdo.data : 0;
    if (size) *size = sdo.size;
    return sdo.kind == canopen::SdoKind::upload_response ? sdo.data : 0;
  }
  void controlword(std::uint16_t cw) { EXPECT_EQ(write(cia402::kControlword, 0, cw, 2), 0u); }
  /// Maps RPDO1 = controlword + target, TPDO1 = statusword + position actual, both on SYNC.
  void map_csp_pdos() {
    EXPECT_EQ(write(0x1400, 1, canopen::kPdoInvalid | canopen::rpdo_cob_id(1, node), 4), 0u);
    EXPECT_EQ(write(0x1600, 0, 0, 1), 0u);
    EXPECT_EQ(write(0x1600, 1, canopen::pdo_mapping_entry(cia402::kControlword, 0, 16), 4), 0u);
    EXPECT_EQ(write(0x1600, 2, canopen::pdo_mapping_entry(cia402::kTargetPosition, 0, 32), 4), 0u);
    EXPECT_EQ(write(0x1600, 0, 2, 1), 0u);
    EXPECT_EQ(write(0x1400, 2, 1, 1), 0u);
    EXPECT_EQ(write(0x1400, 1, canopen::rpdo_cob_id(1, node), 4), 0u);
    EXPECT_EQ(write(0x1800, 1, canopen::kPdoInvalid | canopen::tpdo_cob_id(1, node), 4), 0u);
    EXPECT_EQ(write(0x1A00, 0, 0, 1), 0u);
    EXPECT_EQ(write(0x1A00, 1, canopen::pdo_mapping_entry(cia402::kStatusword, 0, 16), 4), 0u);
    EXPECT_EQ(write(0x1A00, 2, canopen::pdo_mapping_entry(cia402::kPositionActual, 0, 32), 4), 0u);
    EXPECT_EQ(write(0x1A00, 0, 2, 1), 0u);
    EXPECT_EQ(write(0x1800, 2, 1, 1), 0u);
    EXPECT_EQ(write(0x1800, 1, canopen::tpdo_cob_id(1, node), 4), 0u);
  }
  /// Ready for CSP: booted, CSP mode, PDOs mapped, Operational, Operation enabled.
  void enable_csp() {
    wait(0.005);
    EXPECT_EQ(write(cia402::kModesOfOperation, 0, 8, 1), 0u);
    EXPECT_EQ(write(cia402::kTargetPosition, 0, static_cast<std::uint32_t>(drive.object(cia402::kPositionActual)), 4), 0u);
    map_csp_pdos();
    put(canopen::encode_nmt(canopen::NmtCommand::start, node));
    controlword(cia402::kShutdown);
    controlword(cia402::kSwitchOn);
    controlword(cia402::kEnableOperation);
    wait(0.002);
    EXPECT_EQ(drive.state(), Cia402State::operation_enabled);
  }
  std::vector<CanFrame> frames_on(std::uint32_t id) const {
    std::vector<CanFrame> r;
    for (const CanFrame& f : out)
      if (f.id == id) r.push_back(f);
    return r;
  }

  SimCia402Drive drive;
  std::uint8_t node;
  std::vector<CanFrame> out;
};

SimCia402DriveConfig cia402_sim_config(std::uint8_t node = 5) {
  SimCia402DriveConfig c;
  c.node = node;
  c.initial_position = 1000;
  c.position_min = -100000;
  c.position_max = 100000;
  return c;
}

TEST(SimCia402Drive, PowerUpSendsBootUpAndReachesSwitchOnDisabled) {
  Cia402SimBench b(cia402_sim_config());
  ASSERT_EQ(b.out.size(), 1u);
  const std::uint8_t boot[1] = {0x00};
  EXPECT_EQ(b.out[0], firmware_iface::can_data_frame(0x705, boot));
  EXPECT_EQ(b.drive.nmt_state(), canopen::NmtState::pre_operational);
  EXPECT_EQ(b.drive.state(), Cia402State::not_ready_to_switch_on);  // transition 0
  EXPECT_EQ(b.drive.last_transition(), 0);
  b.wait(0.003);
  EXPECT_EQ(b.drive.state(), Cia402State::switch_on_disabled);
  EXPECT_EQ(b.drive.last_transition(), 1);
  EXPECT_EQ(cia402::decode_state(static_cast<std::uint16_t>(b.read(cia402::kStatusword, 0))), Cia402State::switch_on_disabled);
  EXPECT_EQ(b.read(canopen::kDeviceType, 0), 0x00020192u);
  EXPECT_NEAR(b.drive.position_counts(), 1000, 1e-6);
  EXPECT_EQ(b.drive.object(cia402::kPositionActual), 1000);
}

TEST(SimCia402Drive, EveryTransitionOfThePowerStateMachine) {
  Cia402SimBench b(cia402_sim_config());
  b.wait(0.003);
  const auto step = [&](std::uint16_t cw, Cia402State expected, int transition) {
    b.controlword(cw);
    EXPECT_EQ(b.drive.state(), expected) << "transition " << transition;
    EXPECT_EQ(b.drive.last_transition(), transition);
    EXPECT_EQ(cia402::decode_state(static_cast<std::uint16_t>(b.read(cia402::kStatusword, 0))), expected)
        << "transition " << transition;
  };
  step(cia402::kShutdown, Cia402State::ready_to_switch_on, 2);
  step(cia402::kSwitchOn, Cia402State::switched_on, 3);
  step(cia402::kEnableOperation, Cia402State::operation_enabled, 4);
  step(cia402::kDisableOperation, Cia402State::switched_on, 5);
  step(cia402::kShutdown, Cia402State::ready_to_switch_on, 6);
  step(cia402::kDisableVoltage, Cia402State::switch_on_disabled, 7);
  step(cia402::kShutdown, Cia402State::ready_to_switch_on, 2);
  step(cia402::kQuickStop, Cia402State::switch_on_disabled, 7);
  step(cia402::kShutdown, Cia402State::ready_to_switch_on, 2);
  step(cia402::kEnableOperation, Cia402State::operation_enabled, 4);  // 3 then 4 in one command
  step(cia402::kShutdown, Cia402State::ready_to_switch_on, 8);
  step(cia402::kEnableOperation, Cia402State::operation_enabled, 4);
  step(cia402::kDisableVoltage, Cia402State::switch_on_disabled, 9);
  step(cia402::kShutdown, Cia402State::ready_to_switch_on, 2);
  step(cia402::kSwitchOn, Cia402State::switched_on, 3);
  step(cia402::kDisableVoltage, Cia402State::switch_on_disabled, 10);
  step(cia402::kShutdown, Cia402State::ready_to_switch_on, 2);
  step(cia402::kSwitchOn, Cia402State::switched_on, 3);
  step(cia402::kQuickStop, Cia402State::switch_on_disabled, 10);
  step(cia402::kShutdown, Cia402State::ready_to_switch_on, 2);
  step(cia402::kEnableOperation, Cia402State::operation_enabled, 4);
  step(cia402::kQuickStop, Cia402State::quick_stop_active, 11);
  step(cia402::kEnableOperation, Cia402State::operation_enabled, 16);
  step(cia402::kQuickStop, Cia402State::quick_stop_active, 11);
  step(cia402::kDisableVoltage, Cia402State::switch_on_disabled, 12);

  // 13 and 14: a fault from Operation enabled, then Fault once the reaction is over.
  step(cia402::kShutdown, Cia402State::ready_to_switch_on, 2);
  step(cia402::kEnableOperation, Cia402State::operation_enabled, 4);
  b.drive.raise_fault(0x2310);
  EXPECT_EQ(b.drive.state(), Cia402State::fault_reaction_active);
  EXPECT_EQ(b.drive.last_transition(), 13);
  b.wait(0.01);
  EXPECT_EQ(b.drive.state(), Cia402State::fault);
  EXPECT_EQ(b.drive.last_transition(), 14);
  // Nothing but a fault reset leaves Fault, and only on bit 7's rising edge.
  b.controlword(cia402::kEnableOperation);
  EXPECT_EQ(b.drive.state(), Cia402State::fault);
  step(cia402::kFaultReset, Cia402State::switch_on_disabled, 15);
  b.drive.raise_fault(0x2310);
  b.wait(0.01);
  b.controlword(cia402::kFaultReset);  // bit 7 still high: no edge
  EXPECT_EQ(b.drive.state(), Cia402State::fault);
  b.controlword(cia402::kDisableVoltage);
  step(cia402::kFaultReset, Cia402State::switch_on_disabled, 15);
}

TEST(SimCia402Drive, FaultSendsEmcyAndFreesTheMotor) {
  Cia402SimBench b(cia402_sim_config());
  b.enable_csp();
  b.out.clear();
  b.drive.raise_fault(0x7121);
  b.collect();
  const auto emcy = b.frames_on(0x085);
  ASSERT_EQ(emcy.size(), 1u);
  std::uint8_t node = 0;
  canopen::Emcy e;
  ASSERT_TRUE(canopen::decode_emcy(emcy[0], &node, &e));
  EXPECT_EQ(e.error_code, 0x7121);
  EXPECT_EQ(e.error_register & 0x01, 0x01);
  EXPECT_EQ(b.drive.object(cia402::kErrorCode), 0x7121);
  EXPECT_EQ(b.drive.object(canopen::kErrorRegister), e.error_register);
  b.wait(0.01);
  EXPECT_EQ(b.drive.state(), Cia402State::fault);
  // In Fault the drive follows no target.
  b.put(cia402::encode_control_target(0x205, cia402::kEnableOperation, 30000));
  b.put(canopen::encode_sync());
  b.wait(0.05);
  EXPECT_NEAR(b.drive.position_counts(), 1000, 5);
  b.out.clear();
  b.controlword(cia402::kFaultReset);
  // Error reset EMCY, 0x603F cleared.
  const auto reset = b.frames_on(0x085);
  ASSERT_EQ(reset.size(), 1u);
  ASSERT_TRUE(canopen::decode_emcy(reset[0], &node, &e));
  EXPECT_EQ(e.error_code, 0x0000);
  EXPECT_EQ(b.drive.object(cia402::kErrorCode), 0);
}

TEST(SimCia402Drive, SdoAbortForEachCase) {
  Cia402SimBench b(cia402_sim_config());
  b.wait(0.003);
  std::uint32_t abort = 0;
  b.read(0x6099, 0, &abort);
  EXPECT_EQ(abort, canopen::kSdoAbortNoObject);
  b.read(cia402::kControlword, 1, &abort);
  EXPECT_EQ(abort, canopen::kSdoAbortNoSubIndex);
  EXPECT_EQ(b.write(0x6099, 0, 1, 1), canopen::kSdoAbortNoObject);
  EXPECT_EQ(b.write(cia402::kControlword, 3, 1, 2), canopen::kSdoAbortNoSubIndex);
  EXPECT_EQ(b.write(cia402::kStatusword, 0, 0, 2), canopen::kSdoAbortWriteReadOnly);
  EXPECT_EQ(b.write(cia402::kPositionActual, 0, 0, 4), canopen::kSdoAbortWriteReadOnly);
  EXPECT_EQ(b.write(cia402::kControlword, 0, 6, 4), canopen::kSdoAbortLengthTooHigh);
  EXPECT_EQ(b.write(cia402::kTargetPosition, 0, 6, 2), canopen::kSdoAbortLengthTooLow);
  // Size not indicated (0x22) with more than the object holds.
  b.out.clear();
  const std::uint8_t unsized[8] = {0x22, 0x40, 0x60, 0x00, 0x06, 0x00, 0x01, 0x00};
  b.put(firmware_iface::can_data_frame(0x605, unsized));
  EXPECT_EQ(b.answer().data, canopen::kSdoAbortLengthMismatch);
  // ... and within it: accepted.
  const std::uint8_t unsized_ok[8] = {0x22, 0x40, 0x60, 0x00, 0x06, 0x00, 0x00, 0x00};
  b.put(firmware_iface::can_data_frame(0x605, unsized_ok));
  EXPECT_EQ(b.answer().kind, canopen::SdoKind::download_response);
  EXPECT_EQ(b.drive.state(), Cia402State::ready_to_switch_on);
  // A mode the drive does not support.
  EXPECT_EQ(b.write(cia402::kModesOfOperation, 0, 1, 1), canopen::kSdoAbortValueRange);
  // Target beyond the software position limits.
  EXPECT_EQ(b.write(cia402::kTargetPosition, 0, 100001, 4), canopen::kSdoAbortValueTooHigh);
  EXPECT_EQ(b.write(cia402::kTargetPosition, 0, static_cast<std::uint32_t>(-100001), 4), canopen::kSdoAbortValueTooLow);
  EXPECT_EQ(b.write(0x1600, 0, 9, 1), canopen::kSdoAbortValueTooHigh);
  // Reserved transmission types.
  EXPECT_EQ(b.write(0x1400, 2, 241, 1), canopen::kSdoAbortValueRange);
  EXPECT_EQ(b.write(0x1800, 2, 251, 1), canopen::kSdoAbortValueRange);
  // The mapping of a valid PDO cannot change.
  EXPECT_EQ(b.write(0x1600, 0, 0, 1), canopen::kSdoAbortDeviceState);
  EXPECT_EQ(b.write(0x1A00, 1, canopen::pdo_mapping_entry(cia402::kPositionActual, 0, 32), 4), canopen::kSdoAbortDeviceState);
  // ... nor a valid PDO's identifier.
  EXPECT_EQ(b.write(0x1400, 1, 0x333, 4), canopen::kSdoAbortValueRange);
  // Invalidated, with the count at 0: entries are checked against the dictionary.
  EXPECT_EQ(b.write(0x1400, 1, canopen::kPdoInvalid | 0x205, 4), 0u);
  EXPECT_EQ(b.write(0x1600, 1, canopen::pdo_mapping_entry(cia402::kTargetPosition, 0, 32), 4),
            canopen::kSdoAbortDeviceState);  // count 1
  EXPECT_EQ(b.write(0x1600, 0, 0, 1), 0u);
  EXPECT_EQ(b.write(0x1600, 1, canopen::pdo_mapping_entry(canopen::kHeartbeatProducerTime, 0, 16), 4),
            canopen::kSdoAbortCannotMap);
  EXPECT_EQ(b.write(0x1600, 1, canopen::pdo_mapping_entry(cia402::kStatusword, 0, 16), 4),
            canopen::kSdoAbortCannotMap);  // TPDO only
  EXPECT_EQ(b.write(0x1600, 1, canopen::pdo_mapping_entry(cia402::kTargetPosition, 0, 16), 4),
            canopen::kSdoAbortCannotMap);  // wrong length
  EXPECT_EQ(b.write(0x1600, 1, canopen::pdo_mapping_entry(0x6099, 0, 32), 4), canopen::kSdoAbortCannotMap);
  EXPECT_EQ(b.write(0x1600, 0, 3, 1), canopen::kSdoAbortValueRange);  // entry 3 was never written
  for (std::uint8_t s = 1; s <= 3; ++s)
    EXPECT_EQ(b.write(0x1600, s, canopen::pdo_mapping_entry(cia402::kTargetPosition, 0, 32), 4), 0u);
  EXPECT_EQ(b.write(0x1600, 0, 3, 1), canopen::kSdoAbortPdoTooLong);  // 96 bits
  EXPECT_EQ(b.write(0x1600, 0, 2, 1), 0u);
  // A segmented download, a block transfer and a stray response.
  b.out.clear();
  const std::uint8_t segmented[8] = {0x21, 0x7A, 0x60, 0x00, 4, 0, 0, 0};
  b.put(firmware_iface::can_data_frame(0x605, segmented));
  EXPECT_EQ(b.answer().data, canopen::kSdoAbortUnsupportedAccess);
  const std::uint8_t block[8] = {0xC6, 0x7A, 0x60, 0x00, 4, 0, 0, 0};
  b.put(firmware_iface::can_data_frame(0x605, block));
  EXPECT_EQ(b.answer().data, canopen::kSdoAbortInvalidCommand);
  EXPECT_EQ(b.drive.sdo_aborts_sent(), 27u);
}

TEST(SimCia402Drive, DictionaryRefusesReadingAWriteOnlyEntry) {
  // The drive has no write-only object; the dictionary under it knows the case.
  CanopenObjectDictionary od;
  od.add({0x2000, 1, 4, false, ObjectAccess::write_only, PdoMappable::no, false, 0, 0, 0});
  od.add({0x2001, 0, 1, true, ObjectAccess::read_write, PdoMappable::both, true, -5, 5, 0});
  const ObjectEntry* read_entry = nullptr;
  EXPECT_EQ(od.check_read(0x2000, 1, &read_entry), canopen::kSdoAbortReadWriteOnly);
  ObjectEntry* entry = nullptr;
  std::uint32_t raw = 0;
  EXPECT_EQ(od.check_write(0x2000, 1, 7, 4, &entry, &raw), 0u);
  EXPECT_EQ(od.check_write(0x2001, 0, 6, 1, &entry, &raw), canopen::kSdoAbortValueTooHigh);
  EXPECT_EQ(od.check_write(0x2001, 0, 0xFA, 1, &entry, &raw), canopen::kSdoAbortValueTooLow);  // -6
  EXPECT_EQ(od.check_write(0x2001, 0, 0xFB, 1, &entry, &raw), 0u);                             // -5
  EXPECT_EQ(entry->index, 0x2001);
  EXPECT_EQ(raw, 0xFBu);
  EXPECT_TRUE(od.can_map(0x2001, 0, 8, true));
  EXPECT_FALSE(od.can_map(0x2000, 1, 32, false));
}

TEST(SimCia402Drive, DictionaryFindsEntriesInAnyAddedOrderAndRefusesARepeatedOne) {
  CanopenObjectDictionary od;
  od.add({0x6041, 0, 2, false, ObjectAccess::read_only, PdoMappable::tpdo, false, 0, 0, 0x0237});
  od.add({0x1017, 0, 2, false, ObjectAccess::read_write, PdoMappable::no, false, 0, 0, 0});
  od.add({0x1600, 2, 4, false, ObjectAccess::read_write, PdoMappable::no, false, 0, 0, 0});
  od.add({0x1600, 0, 1, false, ObjectAccess::read_write, PdoMappable::no, false, 0, 0, 2});
  EXPECT_EQ(od.get(0x6041, 0), 0x0237u);
  EXPECT_EQ(od.get(0x1600, 0), 2u);
  ASSERT_NE(od.find(0x1600, 2), nullptr);
  EXPECT_EQ(od.find(0x1600, 2)->size, 4);
  EXPECT_EQ(od.find(0x1600, 1), nullptr);
  const ObjectEntry* entry = nullptr;
  EXPECT_EQ(od.check_read(0x1600, 1, &entry), canopen::kSdoAbortNoSubIndex);
  EXPECT_EQ(od.check_read(0x1601, 0, &entry), canopen::kSdoAbortNoObject);
  EXPECT_EQ(od.check_read(0x0FFF, 0, &entry), canopen::kSdoAbortNoObject);
  EXPECT_EQ(od.check_read(0x6042, 0, &entry), canopen::kSdoAbortNoObject);
  EXPECT_THROW(od.add({0x1017, 0, 2, false, ObjectAccess::read_only, PdoMappable::no, false, 0, 0, 0}), std::invalid_argument);
}

TEST(SimCia402Drive, NmtStatesAndResets) {
  Cia402SimBench b(cia402_sim_config(3));
  b.wait(0.003);
  b.controlword(cia402::kShutdown);
  EXPECT_EQ(b.write(canopen::kHeartbeatProducerTime, 0, 50, 2), 0u);
  b.put(canopen::encode_nmt(canopen::NmtCommand::start, 3));
  EXPECT_EQ(b.drive.nmt_state(), canopen::NmtState::operational);
  b.put(canopen::encode_nmt(canopen::NmtCommand::stop, 0));  // all nodes
  EXPECT_EQ(b.drive.nmt_state(), canopen::NmtState::stopped);
  // Stopped: no SDO.
  b.out.clear();
  b.put(canopen::encode_sdo_upload(3, cia402::kStatusword, 0));
  EXPECT_TRUE(b.out.empty());
  b.put(canopen::encode_nmt(canopen::NmtCommand::enter_pre_operational, 4));  // another node
  EXPECT_EQ(b.drive.nmt_state(), canopen::NmtState::stopped);
  b.put(canopen::encode_nmt(canopen::NmtCommand::enter_pre_operational, 3));
  EXPECT_EQ(b.drive.nmt_state(), canopen::NmtState::pre_operational);
  // Reset communication: boot-up, communication objects back to their defaults, the drive's
  // state untouched.
  b.out.clear();
  b.put(canopen::encode_nmt(canopen::NmtCommand::reset_communication, 3));
  ASSERT_EQ(b.out.size(), 1u);
  EXPECT_EQ(b.out[0].id, 0x703u);
  EXPECT_EQ(b.out[0].data[0], 0x00);
  EXPECT_EQ(b.drive.nmt_state(), canopen::NmtState::pre_operational);
  EXPECT_EQ(b.read(canopen::kHeartbeatProducerTime, 0), 0u);
  EXPECT_EQ(b.drive.state(), Cia402State::ready_to_switch_on);
  // Reset node: the application too.
  b.put(canopen::encode_nmt(canopen::NmtCommand::reset_node, 3));
  EXPECT_EQ(b.drive.state(), Cia402State::not_ready_to_switch_on);
  EXPECT_EQ(b.drive.last_transition(), 0);
  b.wait(0.003);
  EXPECT_EQ(b.drive.state(), Cia402State::switch_on_disabled);
}

TEST(SimCia402Drive, HeartbeatProducerFollows0x1017) {
  Cia402SimBench b(cia402_sim_config(2));
  b.wait(0.01);
  EXPECT_TRUE(b.frames_on(0x702).size() == 1);  // the boot-up only
  EXPECT_EQ(b.write(canopen::kHeartbeatProducerTime, 0, 20, 2), 0u);
  b.out.clear();
  b.wait(0.1);
  auto beats = b.frames_on(0x702);
  ASSERT_EQ(beats.size(), 5u);
  EXPECT_EQ(beats[0].data[0], 0x7F);  // Pre-operational
  b.put(canopen::encode_nmt(canopen::NmtCommand::start, 2));
  b.out.clear();
  b.wait(0.04);
  beats = b.frames_on(0x702);
  ASSERT_EQ(beats.size(), 2u);
  EXPECT_EQ(beats[0].data[0], 0x05);
  b.drive.set_heartbeat_silent(true);
  b.out.clear();
  b.wait(0.1);
  EXPECT_TRUE(b.frames_on(0x702).empty());
  b.drive.set_heartbeat_silent(false);
  b.wait(0.1);
  EXPECT_EQ(b.frames_on(0x702).size(), 5u);
}

TEST(SimCia402Drive, PdosRunOnlyInOperationalAndOnSync) {
  Cia402SimBench b(cia402_sim_config());
  b.wait(0.003);
  EXPECT_EQ(b.write(cia402::kModesOfOperation, 0, 8, 1), 0u);
  b.map_csp_pdos();
  // Pre-operational: RPDOs and SYNC are ignored.
  b.out.clear();
  b.put(cia402::encode_control_target(0x205, cia402::kShutdown, 1000));
  b.put(canopen::encode_sync());
  EXPECT_TRUE(b.out.empty());
  EXPECT_EQ(b.drive.state(), Cia402State::switch_on_disabled);
  b.put(canopen::encode_nmt(canopen::NmtCommand::start, 5));
  // A synchronous RPDO waits for the SYNC.
  b.put(cia402::encode_control_target(0x205, cia402::kShutdown, 1000));
  EXPECT_EQ(b.drive.state(), Cia402State::switch_on_disabled);
  b.out.clear();
  b.put(canopen::encode_sync());
  EXPECT_EQ(b.drive.state(), Cia402State::ready_to_switch_on);
  // The TPDO answers the SYNC with the state after it.
  ASSERT_EQ(b.out.size(), 1u);
  std::uint16_t sw = 0;
  std::int32_t position = 0;
  ASSERT_TRUE(cia402::decode_status_position(b.out[0], 0x185, &sw, &position));
  EXPECT_EQ(cia402::decode_state(sw), Cia402State::ready_to_switch_on);
  EXPECT_EQ(position, 1000);
  // A short RPDO is refused with an EMCY.
  b.out.clear();
  const std::uint8_t short_pdo[2] = {0x0F, 0x00};
  b.put(firmware_iface::can_data_frame(0x205, short_pdo));
  ASSERT_EQ(b.frames_on(0x085).size(), 1u);
  EXPECT_EQ(b.frames_on(0x085)[0].data[0], 0x10);
  EXPECT_EQ(b.frames_on(0x085)[0].data[1], 0x82);
  // Transmission type 2: every second SYNC (changed while the PDO is invalid).
  EXPECT_EQ(b.write(0x1800, 1, canopen::kPdoInvalid | 0x185, 4), 0u);
  EXPECT_EQ(b.write(0x1800, 2, 2, 1), 0u);
  EXPECT_EQ(b.write(0x1800, 1, 0x185, 4), 0u);
  b.out.clear();
  for (int i = 0; i < 6; ++i) b.put(canopen::encode_sync());
  EXPECT_EQ(b.frames_on(0x185).size(), 3u);
  EXPECT_EQ(b.drive.syncs(), 7u);
}

TEST(SimCia402Drive, DefaultEventTpdoSendsTheStatuswordOnChange) {
  Cia402SimBench b(cia402_sim_config());
  b.wait(0.003);
  b.put(canopen::encode_nmt(canopen::NmtCommand::start, 5));
  // The first one on entering Operational, then one per change.
  ASSERT_EQ(b.frames_on(0x185).size(), 1u);
  EXPECT_EQ(b.frames_on(0x185)[0].dlc, 2);
  b.out.clear();
  b.controlword(cia402::kShutdown);
  b.wait(0.01);
  const auto tpdos = b.frames_on(0x185);
  ASSERT_EQ(tpdos.size(), 1u);
  EXPECT_EQ(cia402::decode_state(static_cast<std::uint16_t>(tpdos[0].data[0] | tpdos[0].data[1] << 8)),
            Cia402State::ready_to_switch_on);
  // Default RPDO1 (controlword, event-driven) acts at once.
  b.put(firmware_iface::can_data_frame(0x205, std::vector<std::uint8_t>{0x07, 0x00}));
  EXPECT_EQ(b.drive.state(), Cia402State::switched_on);
}

TEST(SimCia402Drive, CspFollowsTheStreamedTarget) {
  Cia402SimBench b(cia402_sim_config());
  b.enable_csp();
  EXPECT_NEAR(b.drive.position_counts(), 1000, 1);
  // A ramp of 20 000 counts/s (about 0.3 turn/s), one target per 5 ms SYNC period.
  double target = 1000;
  double worst = 0;
  for (int tick = 0; tick < 200; ++tick) {
    target += 100;
    b.put(cia402::encode_control_target(0x205, cia402::kEnableOperation, static_cast<std::int32_t>(target)));
    b.put(canopen::encode_sync());
    b.wait(0.005);
    if (tick > 20) worst = std::max(worst, std::abs(b.drive.position_counts() - target));
  }
  EXPECT_LT(worst, 150);  // under two periods' worth of lag
  EXPECT_EQ(b.drive.object(cia402::kTargetPosition), 21000);
  // Targets beyond the software limits are clamped.
  b.put(cia402::encode_control_target(0x205, cia402::kEnableOperation, 500000));
  b.put(canopen::encode_sync());
  EXPECT_EQ(b.drive.object(cia402::kTargetPosition), 100000);
}

TEST(SimCia402Drive, QuickStopHoldsWhereItStopped) {
  Cia402SimBench b(cia402_sim_config());
  b.enable_csp();
  b.put(cia402::encode_control_target(0x205, cia402::kQuickStop, 50000));
  b.put(canopen::encode_sync());
  EXPECT_EQ(b.drive.state(), Cia402State::quick_stop_active);
  b.wait(0.1);
  EXPECT_NEAR(b.drive.position_counts(), 1000, 5);  // the new target is not followed
}

}  // namespace
}  // namespace avar::sim
