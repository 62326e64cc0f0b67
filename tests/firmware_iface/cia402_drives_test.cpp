// Cia402Drives against SimCia402Drive over DirectCanBus: start from a fresh and from a faulted
// drive, no jump on enable, a streamed ramp tracked, heartbeat loss, drive faults with their
// EMCY code, an SDO abort during start, release.
#include "avar/firmware_iface/cia402_drives.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "../support/direct_can_bus.hpp"
#include "avar/firmware_iface/canopen_sdo_client.hpp"
#include "avar/sim/sim_cia402_drive.hpp"

namespace avar::firmware_iface {
namespace {

using Cia402State = cia402::State;

constexpr double kCia402CountsPerTurn = 65536;
constexpr auto kCia402Tick = std::chrono::milliseconds(10);

/// Degrees on the channel, counts on the drive: one turn = 360° = 65536 counts.
LinearCalibration cia402_degrees() {
  LinearCalibration c;
  c.channel_min = -180;
  c.channel_max = 180;
  c.device_at_min = -kCia402CountsPerTurn / 2;
  c.device_at_max = kCia402CountsPerTurn / 2;
  return c;
}

double cia402_counts_to_degrees(double counts) { return counts * 360 / kCia402CountsPerTurn; }

/// Simulated drives on a direct bus, and the drive set under test running a paced 100 Hz loop.
struct Cia402Rig {
  explicit Cia402Rig(std::vector<sim::SimCia402DriveConfig> sims, std::uint16_t heartbeat_ms = 20,
                     std::uint32_t budget_ticks = 10) {
    std::vector<sim::CanNode*> nodes;
    Cia402DrivesConfig config;
    config.heartbeat_ms = heartbeat_ms;
    config.heartbeat_budget_ticks = budget_ticks;
    for (std::size_t i = 0; i < sims.size(); ++i) {
      sims[i].counts_per_turn = kCia402CountsPerTurn;
      drives.push_back(std::make_unique<sim::SimCia402Drive>(sims[i]));
      nodes.push_back(drives.back().get());
      config.actuators.push_back({i, sims[i].node, cia402_degrees()});
    }
    bus = std::make_unique<test::DirectCanBus>(nodes);
    set = std::make_unique<Cia402Drives>(config);
    outbox = std::make_unique<CanOutbox>(set->max_tick_frames());
    frame.assign(sims.size(), 0.0);
    telemetry.resize(sims.size());
  }

  /// One tick: this frame's RPDOs and SYNC out, then every frame until the tick's end taken.
  Status tick() {
    outbox->clear();
    set->encode_tick(frame, *outbox);
    EXPECT_EQ(bus->send(outbox->frames()), Status::ok);
    const auto deadline = bus->now() + kCia402Tick;
    CanFrame f;
    while (bus->receive(&f, deadline) == Status::ok) set->take(f);
    const Status s = set->settle();
    set->read_telemetry(telemetry);
    return s;
  }
  void release() {
    outbox->clear();
    set->encode_release(*outbox);
    EXPECT_EQ(bus->send(outbox->frames()), Status::ok);
    bus->advance(kCia402Tick);
  }
  /// Every SDO download the host sent to `node`, as (index, sub, value).
  std::vector<std::tuple<std::uint16_t, std::uint8_t, std::uint32_t>> downloads(std::uint8_t node) const {
    std::vector<std::tuple<std::uint16_t, std::uint8_t, std::uint32_t>> r;
    for (const CanFrame& f : bus->sent) {
      std::uint8_t n = 0;
      bool from_server = false;
      canopen::Sdo sdo;
      if (canopen::decode_sdo(f, &n, &from_server, &sdo) && n == node && sdo.kind == canopen::SdoKind::download_request)
        r.emplace_back(sdo.index, sdo.sub, sdo.data);
    }
    return r;
  }

  std::vector<std::unique_ptr<sim::SimCia402Drive>> drives;
  std::unique_ptr<test::DirectCanBus> bus;
  std::unique_ptr<Cia402Drives> set;
  std::unique_ptr<CanOutbox> outbox;
  std::vector<double> frame;
  std::vector<ChannelTelemetry> telemetry;
};

sim::SimCia402DriveConfig cia402_drive(std::uint8_t node, std::int32_t position) {
  sim::SimCia402DriveConfig c;
  c.node = node;
  c.initial_position = position;
  return c;
}

/// Starts the set and puts the frame where the drives say they are.
void cia402_start(Cia402Rig& rig) {
  ASSERT_EQ(rig.set->start(*rig.bus), Status::ok) << rig.set->start_problem();
  bool k[8] = {};
  ASSERT_EQ(rig.set->read_positions(*rig.bus, rig.frame, std::span<bool>(k, rig.frame.size())), Status::ok);
  for (std::size_t i = 0; i < rig.frame.size(); ++i) EXPECT_TRUE(k[i]);
}

TEST(Cia402Drives, FreshDriveReachesOperationEnabledWithoutAJump) {
  Cia402Rig rig({cia402_drive(5, 5000)});
  cia402_start(rig);
  EXPECT_EQ(rig.drives[0]->state(), Cia402State::operation_enabled);
  EXPECT_EQ(rig.drives[0]->nmt_state(), canopen::NmtState::operational);
  EXPECT_EQ(rig.drives[0]->object(cia402::kModesOfOperationDisplay), 8);
  EXPECT_EQ(rig.drives[0]->object(cia402::kTargetPosition), 5000);
  EXPECT_EQ(rig.drives[0]->object(canopen::kHeartbeatProducerTime), 20);
  EXPECT_EQ(rig.set->drive_state(0), Cia402State::operation_enabled);
  EXPECT_NEAR(rig.frame[0], cia402_counts_to_degrees(5000), 1e-9);

  // The configuration as the note describes it, in order.
  const auto w = rig.downloads(5);
  using D = std::tuple<std::uint16_t, std::uint8_t, std::uint32_t>;
  const std::vector<D> expected = {
      {0x6060, 0, 8},          {0x1017, 0, 20},         {0x1400, 1, 0x80000205}, {0x1600, 0, 0},     {0x1600, 1, 0x60400010},
      {0x1600, 2, 0x607A0020}, {0x1600, 0, 2},          {0x1400, 2, 1},          {0x1400, 1, 0x205}, {0x1800, 1, 0x80000185},
      {0x1A00, 0, 0},          {0x1A00, 1, 0x60410010}, {0x1A00, 2, 0x60640020}, {0x1A00, 0, 2},     {0x1800, 2, 1},
      {0x1800, 1, 0x185},      {0x607A, 0, 5000},       {0x6040, 0, 0x06},       {0x6040, 0, 0x07},  {0x6040, 0, 0x0F},
  };
  EXPECT_EQ(w, expected);
  const std::uint8_t reset_comm[2] = {0x82, 5};
  EXPECT_EQ(rig.bus->sent.front(), can_data_frame(0x000, reset_comm));

  // Held where it was: no jump over a second of ticks at the present position.
  double worst = 0;
  for (int i = 0; i < 100; ++i) {
    EXPECT_EQ(rig.tick(), Status::ok);
    worst = std::max(worst, std::abs(rig.drives[0]->position_counts() - 5000));
    EXPECT_EQ(rig.telemetry[0].faults, 0u);
  }
  EXPECT_LT(worst, 2.0);
  EXPECT_NEAR(rig.telemetry[0].position, cia402_counts_to_degrees(5000), 0.05);
  EXPECT_EQ(rig.drives[0]->state(), Cia402State::operation_enabled);
  EXPECT_EQ(rig.drives[0]->syncs(), 100u);
}

TEST(Cia402Drives, FaultedDriveIsResetAndStartsWhereItIs) {
  Cia402Rig rig({cia402_drive(7, -12000)});
  rig.drives[0]->raise_fault(0x3210);
  rig.bus->advance(std::chrono::milliseconds(20));
  ASSERT_EQ(rig.drives[0]->state(), Cia402State::fault);
  cia402_start(rig);
  EXPECT_EQ(rig.drives[0]->state(), Cia402State::operation_enabled);
  const auto w = rig.downloads(7);
  ASSERT_GE(w.size(), 2u);
  EXPECT_EQ(w[0], std::make_tuple(std::uint16_t{0x6040}, std::uint8_t{0}, std::uint32_t{0x0080}));
  EXPECT_EQ(w[1], std::make_tuple(std::uint16_t{0x6040}, std::uint8_t{0}, std::uint32_t{0x0000}));
  for (int i = 0; i < 50; ++i) EXPECT_EQ(rig.tick(), Status::ok);
  EXPECT_NEAR(rig.drives[0]->position_counts(), -12000, 2);
  EXPECT_EQ(rig.telemetry[0].faults, 0u);
}

TEST(Cia402Drives, StreamedRampIsTrackedOnTwoDrives) {
  Cia402Rig rig({cia402_drive(1, 0), cia402_drive(2, 8192)});
  cia402_start(rig);
  const double start0 = rig.frame[0];
  const double start1 = rig.frame[1];
  EXPECT_NEAR(start1, 45, 1e-9);
  double worst_telemetry = 0, worst_truth = 0;
  for (int i = 1; i <= 150; ++i) {
    // 60°/s up on one, down on the other, then held.
    const double s = std::min(i, 100) * 0.6;
    rig.frame[0] = start0 + s;
    rig.frame[1] = start1 - s;
    ASSERT_EQ(rig.tick(), Status::ok);
    worst_truth = std::max(worst_truth, std::abs(cia402_counts_to_degrees(rig.drives[0]->position_counts()) - rig.frame[0]));
    worst_telemetry = std::max(worst_telemetry, std::abs(rig.telemetry[1].position - rig.frame[1]));
  }
  EXPECT_LT(worst_truth, 1.0);      // under two ticks of ramp
  EXPECT_LT(worst_telemetry, 1.5);  // telemetry is the previous SYNC's sample
  EXPECT_NEAR(cia402_counts_to_degrees(rig.drives[0]->position_counts()), 60, 0.05);
  EXPECT_NEAR(rig.telemetry[1].position, -15, 0.05);
  EXPECT_EQ(rig.telemetry[0].updates, 150u);
  EXPECT_EQ(rig.set->saturated(), 0u);
}

TEST(Cia402Drives, HeartbeatLossIsSeenWithinTheBudget) {
  Cia402Rig rig({cia402_drive(5, 0)}, 20, 10);  // 20 ms heartbeats, 10 ticks of 10 ms
  cia402_start(rig);
  for (int i = 0; i < 30; ++i) {
    ASSERT_EQ(rig.tick(), Status::ok);
    ASSERT_EQ(rig.telemetry[0].faults, 0u) << "tick " << i;
  }
  rig.drives[0]->set_heartbeat_silent(true);
  int ticks = 0;
  while (!(rig.telemetry[0].faults & kDeviceLost) && ticks < 50) {
    EXPECT_EQ(rig.tick(), Status::ok);  // the TPDOs still come
    ++ticks;
  }
  // Lost on the 10th tick in a row without a heartbeat (the budget), counted from the last
  // heartbeat (at most one heartbeat period, 2 ticks, before the silence began).
  EXPECT_GE(ticks, 9);
  EXPECT_LE(ticks, 11);
  EXPECT_EQ(rig.set->channel_problem(0), "CiA 402 node 5: no heartbeat for 10 ticks");
  rig.drives[0]->set_heartbeat_silent(false);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(rig.tick(), Status::ok);
  EXPECT_EQ(rig.telemetry[0].faults & kDeviceLost, 0u);
}

TEST(Cia402Drives, DriveFaultIsSeenWithItsEmcyCode) {
  Cia402Rig rig({cia402_drive(5, 1000), cia402_drive(6, 2000)});
  cia402_start(rig);
  for (int i = 0; i < 5; ++i) ASSERT_EQ(rig.tick(), Status::ok);
  rig.drives[0]->raise_fault(0x7121);
  ASSERT_EQ(rig.tick(), Status::ok);
  EXPECT_TRUE(rig.telemetry[0].faults & kDeviceFaultState);
  EXPECT_TRUE(rig.telemetry[0].faults & kDeviceOverload);
  EXPECT_EQ(rig.telemetry[1].faults, 0u);
  EXPECT_EQ(rig.set->drive_state(0), Cia402State::fault_reaction_active);
  ASSERT_EQ(rig.tick(), Status::ok);
  EXPECT_EQ(rig.set->drive_state(0), Cia402State::fault);
  EXPECT_EQ(rig.set->channel_problem(0), "CiA 402 node 5: Fault (EMCY 0x7121)");
  EXPECT_EQ(rig.set->channel_problem(1), "");
  EXPECT_EQ(rig.set->device_errors(), 1u);
}

TEST(Cia402Drives, LeavingOperationEnabledOrOperationalWhileDrivenIsAFaultState) {
  Cia402Rig rig({cia402_drive(5, 0)});
  cia402_start(rig);
  ASSERT_EQ(rig.tick(), Status::ok);
  // Someone else on the bus sends the drive to Pre-operational: no more PDOs, a heartbeat says so.
  const CanFrame pre_op = canopen::encode_nmt(canopen::NmtCommand::enter_pre_operational, 5);
  ASSERT_EQ(rig.bus->send(std::span<const CanFrame>(&pre_op, 1)), Status::ok);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(rig.tick(), Status::timeout);  // no TPDO: feedback unknown
  EXPECT_TRUE(std::isnan(rig.telemetry[0].position));
  EXPECT_TRUE(rig.telemetry[0].faults & kDeviceFaultState);
  EXPECT_EQ(rig.set->channel_problem(0), "CiA 402 node 5: NMT Pre-operational, not Operational");

  Cia402Rig other({cia402_drive(3, 0)});
  cia402_start(other);
  ASSERT_EQ(other.tick(), Status::ok);
  // Voltage disabled from elsewhere (another master, the drive's own input): the cyclic 0x000F
  // does not switch it back on.
  ASSERT_EQ(
      canopen::sdo_download(*other.bus, 3, cia402::kControlword, 0, cia402::kDisableVoltage, 2, std::chrono::milliseconds(10))
          .status,
      Status::ok);
  ASSERT_EQ(other.tick(), Status::ok);
  EXPECT_EQ(other.set->drive_state(0), Cia402State::switch_on_disabled);
  EXPECT_TRUE(other.telemetry[0].faults & kDeviceFaultState);
  EXPECT_EQ(other.set->channel_problem(0), "CiA 402 node 3: left Operation enabled for Switch on disabled");
}

TEST(Cia402Drives, SdoAbortDuringStartNamesNodeObjectAndAbort) {
  sim::SimCia402DriveConfig pp_only = cia402_drive(5, 0);
  pp_only.supported_modes = 1u << 0;  // profile position only
  Cia402Rig rig({pp_only});
  EXPECT_EQ(rig.set->start(*rig.bus), Status::out_of_range);
  EXPECT_EQ(rig.set->start_problem(), "CiA 402 node 5: SDO abort 0x06090030 (value range exceeded) writing 0x6060:00");
  EXPECT_EQ(rig.drives[0]->state(), Cia402State::switch_on_disabled);
}

TEST(Cia402Drives, AbsentDriveFailsStartWithItsNode) {
  Cia402Rig rig({cia402_drive(5, 0)});
  rig.bus->set_attached(rig.drives[0].get(), false);
  EXPECT_EQ(rig.set->start(*rig.bus), Status::timeout);
  EXPECT_EQ(rig.set->start_problem(), "CiA 402 node 5: no boot-up within 1000 ms of NMT reset communication (timeout)");
}

TEST(Cia402Drives, ReleaseSwitchesTheDrivesOff) {
  Cia402Rig rig({cia402_drive(5, 100), cia402_drive(6, 200)});
  cia402_start(rig);
  for (int i = 0; i < 3; ++i) ASSERT_EQ(rig.tick(), Status::ok);
  // One channel released: controlword 0x0000 once, the drive goes to Switch on disabled and that
  // is no fault; the other drive goes on.
  rig.set->release_channel(1);
  const std::size_t sent_before = rig.bus->sent.size();
  ASSERT_EQ(rig.tick(), Status::ok);
  EXPECT_EQ(rig.drives[1]->state(), Cia402State::switch_on_disabled);
  EXPECT_EQ(rig.drives[0]->state(), Cia402State::operation_enabled);
  std::uint16_t cw = 0xFFFF;
  std::int32_t target = 0;
  ASSERT_TRUE(cia402::decode_control_target(rig.bus->sent[sent_before + 1], 0x206, &cw, &target));
  EXPECT_EQ(cw, 0x0000);
  EXPECT_EQ(target, 200);
  const std::size_t sent_after = rig.bus->sent.size();
  ASSERT_EQ(rig.tick(), Status::ok);
  EXPECT_EQ(rig.bus->sent.size() - sent_after, 2u);  // node 5's RPDO and the SYNC only
  EXPECT_EQ(rig.telemetry[1].faults, 0u);
  EXPECT_EQ(rig.set->drive_state(1), Cia402State::switch_on_disabled);

  rig.release();
  EXPECT_EQ(rig.drives[0]->state(), Cia402State::switch_on_disabled);
  EXPECT_EQ(rig.drives[1]->state(), Cia402State::switch_on_disabled);
  EXPECT_EQ(rig.set->max_tick_frames(), 3u);
}

TEST(Cia402Drives, ConfigIsChecked) {
  Cia402DrivesConfig bad;
  bad.actuators = {{0, 0, cia402_degrees()}};
  EXPECT_THROW(Cia402Drives{bad}, std::invalid_argument);
  bad.actuators = {{0, 128, cia402_degrees()}};
  EXPECT_THROW(Cia402Drives{bad}, std::invalid_argument);
  bad.actuators = {{0, 4, cia402_degrees()}, {1, 4, cia402_degrees()}};
  EXPECT_THROW(Cia402Drives{bad}, std::invalid_argument);
}

}  // namespace
}  // namespace avar::firmware_iface
