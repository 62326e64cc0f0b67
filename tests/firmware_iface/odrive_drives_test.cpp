// OdriveDrives against simulated ODrive axes over a direct CAN bus: start from the present
// positions, streaming, heartbeat loss, axis errors, release, and noise on the bus.
#include "avar/firmware_iface/odrive_drives.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <deque>
#include <memory>
#include <stdexcept>
#include <vector>

#include "../support/direct_can_bus.hpp"
#include "avar/sim/sim_odrive_axis.hpp"

namespace avar::firmware_iface {
namespace {

namespace od = odrive;
using namespace std::chrono_literals;

constexpr std::chrono::milliseconds kOdriveTick = 10ms;  // 100 Hz: a heartbeat every 10 ticks

/// Degrees on the channel, turns at the motor: ±1800° is ±5 turns.
LinearCalibration odrive_degrees() { return {-1800, 1800, -5, 5, false, 0}; }

struct OdriveAxisSpec {
  std::uint8_t node;
  double position_turns;
};

/// Simulated axes on a direct bus, and the drive set driving them (actuator i on channel i).
struct OdriveBench {
  explicit OdriveBench(std::vector<OdriveAxisSpec> specs, OdriveDrivesConfig config = {},
                       void (*tweak)(sim::SimOdriveAxisConfig&) = nullptr) {
    std::vector<sim::CanNode*> nodes;
    for (std::size_t i = 0; i < specs.size(); ++i) {
      sim::SimOdriveAxisConfig c;
      c.node = specs[i].node;
      c.initial_position_turns = specs[i].position_turns;
      c.hold_position_on_entry = false;  // the driver must avoid the jump itself
      if (tweak) tweak(c);
      axes.push_back(std::make_unique<sim::SimOdriveAxis>(c));
      nodes.push_back(axes.back().get());
      if (config.actuators.size() <= i) {
        OdriveActuator a;
        a.channel = i;
        a.node = specs[i].node;
        a.calibration = odrive_degrees();
        a.velocity_limit = 4;
        a.current_limit = 20;
        config.actuators.push_back(a);
      }
    }
    bus = std::make_unique<test::DirectCanBus>(nodes);
    drives = std::make_unique<OdriveDrives>(config);
    out = std::make_unique<CanOutbox>(drives->max_tick_frames());
    frame.assign(specs.size(), 0.0);
    telemetry.resize(specs.size());
  }

  /// One tick as a CAN link runs it: encode, send, take every frame already received, settle,
  /// then let a tick period pass.
  Status tick() {
    out->clear();
    drives->encode_tick(frame, *out);
    EXPECT_EQ(bus->send(out->frames()), Status::ok);
    CanFrame f;
    while (bus->receive(&f, bus->now()) == Status::ok) drives->take(f);
    const Status s = drives->settle();
    drives->read_telemetry(telemetry);
    bus->advance(kOdriveTick);
    return s;
  }

  std::vector<CanFrame> sent_to(std::uint8_t node, std::size_t from = 0) const {
    std::vector<CanFrame> out_frames;
    for (std::size_t k = from; k < bus->sent.size(); ++k)
      if (od::odrive_node(bus->sent[k].id) == node) out_frames.push_back(bus->sent[k]);
    return out_frames;
  }

  std::vector<std::unique_ptr<sim::SimOdriveAxis>> axes;
  std::unique_ptr<test::DirectCanBus> bus;
  std::unique_ptr<OdriveDrives> drives;
  std::unique_ptr<CanOutbox> out;
  std::vector<double> frame;
  std::vector<ChannelTelemetry> telemetry;
};

constexpr std::uint8_t kOdriveClosedLoop = 8, kOdriveIdle = 1;

TEST(OdriveDrives, StartBringsAxesToClosedLoopFromTheirPresentPositions) {
  OdriveBench b({{1, 0.3}, {2, -1.2}, {3, 2.5}}, {}, [](sim::SimOdriveAxisConfig& c) {
    if (c.node == 3) c.closed_loop_entry_s = 0.4;  // slow to arm
  });
  ASSERT_EQ(b.drives->start(*b.bus), Status::ok) << b.drives->start_problem();
  EXPECT_EQ(b.drives->start_problem(), "");
  const double present[] = {0.3, -1.2, 2.5};
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(b.axes[i]->state(), kOdriveClosedLoop);
    EXPECT_NEAR(b.axes[i]->input_pos(), present[i], 1e-3);
    EXPECT_EQ(b.axes[i]->velocity_limit(), 4.0);
    EXPECT_EQ(b.axes[i]->current_limit(), 20.0);
    EXPECT_EQ(b.axes[i]->input_mode(), static_cast<int>(od::InputMode::passthrough));
  }
  // The conversation of one axis, in order.
  const std::vector<CanFrame> node2 = b.sent_to(2);
  ASSERT_EQ(node2.size(), 6u);
  EXPECT_EQ(node2[0], od::encode_clear_errors(2));
  EXPECT_EQ(node2[1], od::encode_get_encoder_estimates(2));
  EXPECT_EQ(node2[2], od::encode_set_controller_modes(2, od::ControlMode::position, od::InputMode::passthrough));
  EXPECT_EQ(node2[3], od::encode_set_limits(2, 4.0f, 20.0f));
  EXPECT_EQ(node2[4].id, od::can_id(2, od::kSetInputPos));
  EXPECT_EQ(node2[5], od::encode_set_axis_state(2, od::AxisState::closed_loop_control));

  // Streaming the positions read back holds every axis still: no jump.
  std::vector<double> positions(3, 0.0);
  bool known[3] = {false, false, false};
  ASSERT_EQ(b.drives->read_positions(*b.bus, positions, known), Status::ok);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_TRUE(known[i]);
    EXPECT_NEAR(positions[i], present[i] * 360, 0.1);
  }
  b.frame = positions;
  for (int t = 0; t < 50; ++t) {
    ASSERT_EQ(b.tick(), Status::ok);
    for (std::size_t i = 0; i < 3; ++i) ASSERT_NEAR(b.axes[i]->position_turns(), present[i], 1e-3) << "tick " << t;
  }
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(b.telemetry[i].position, present[i] * 360, 0.1);
    EXPECT_EQ(b.telemetry[i].faults, 0u);
    EXPECT_EQ(b.telemetry[i].updates, 50u);
  }
}

TEST(OdriveDrives, StreamedRampIsTracked) {
  OdriveBench b({{1, 0.0}, {2, 0.0}});
  ASSERT_EQ(b.drives->start(*b.bus), Status::ok) << b.drives->start_problem();
  // 90°/s and -180°/s for 2 s at 100 Hz; without velocity feed-forward the axis lags by
  // v / pos_gain (20/s): 4.5° and 9°.
  double worst[2] = {0, 0}, worst_telemetry = 0;
  for (int t = 1; t <= 200; ++t) {
    b.frame = {0.9 * t, -1.8 * t};
    ASSERT_EQ(b.tick(), Status::ok);
    const double actual[2] = {b.axes[0]->position_turns() * 360, b.axes[1]->position_turns() * 360};
    if (t > 30)
      for (int i = 0; i < 2; ++i) worst[i] = std::max(worst[i], std::abs(actual[i] - b.frame[i]));
    worst_telemetry = std::max(worst_telemetry, std::abs(b.telemetry[0].position - actual[0]));
  }
  EXPECT_LT(worst[0], 6.0);
  EXPECT_LT(worst[1], 11.0);
  EXPECT_LT(worst_telemetry, 1.0);  // read back one tick period before the ground truth moved on
  EXPECT_NEAR(b.axes[0]->position_turns(), 0.5, 0.02);
  EXPECT_NEAR(b.axes[1]->position_turns(), -1.0, 0.04);
}

TEST(OdriveDrives, CommandsSaturateToTheCalibratedWindow) {
  OdriveBench b({{4, 4.9}});
  ASSERT_EQ(b.drives->start(*b.bus), Status::ok) << b.drives->start_problem();
  b.frame = {5000};  // past +1800° = 5 turns
  ASSERT_EQ(b.tick(), Status::ok);
  EXPECT_EQ(b.axes[0]->input_pos(), 5.0);
  EXPECT_EQ(b.drives->saturated(), 1u);
}

TEST(OdriveDrives, HeartbeatLossIsDeviceLostWithinTheBudget) {
  OdriveDrivesConfig config;
  config.heartbeat_budget_ticks = 30;
  OdriveBench b({{1, 0.0}, {2, 0.0}}, config);
  ASSERT_EQ(b.drives->start(*b.bus), Status::ok) << b.drives->start_problem();
  for (int t = 0; t < 15; ++t) ASSERT_EQ(b.tick(), Status::ok);
  b.axes[1]->set_heartbeat_enabled(false);
  int lost_at = -1;
  for (int t = 1; t <= 45 && lost_at < 0; ++t) {
    ASSERT_EQ(b.tick(), Status::ok);  // estimates still come: only the heartbeat is gone
    EXPECT_EQ(b.telemetry[0].faults, 0u);
    if (b.telemetry[1].faults & kDeviceLost) lost_at = t;
  }
  ASSERT_GT(lost_at, 0);
  EXPECT_LE(lost_at, 31);  // at most the budget (+1) after the last heartbeat (the 30th silent tick)
  EXPECT_GE(lost_at, 21);  // and not before the budget ran out since it (heartbeats every 10 ticks)
  EXPECT_EQ(b.drives->channel_problem(1), "ODrive node 2: no heartbeat for 30 ticks");
  EXPECT_EQ(b.drives->channel_problem(0), "");

  b.axes[1]->set_heartbeat_enabled(true);
  for (int t = 0; t < 11; ++t) ASSERT_EQ(b.tick(), Status::ok);
  EXPECT_EQ(b.telemetry[1].faults, 0u);
  EXPECT_EQ(b.drives->channel_problem(1), "");
}

TEST(OdriveDrives, ADetachedAxisIsLostAndItsPositionUnknown) {
  OdriveBench b({{1, 0.0}, {2, 0.5}});
  ASSERT_EQ(b.drives->start(*b.bus), Status::ok) << b.drives->start_problem();
  ASSERT_EQ(b.tick(), Status::ok);
  EXPECT_NEAR(b.telemetry[1].position, 180, 0.1);
  b.bus->set_attached(b.axes[1].get(), false);
  EXPECT_EQ(b.tick(), Status::timeout);  // its estimate did not come
  EXPECT_FALSE(b.drives->replies_complete());
  EXPECT_TRUE(std::isnan(b.telemetry[1].position));
  EXPECT_FALSE(std::isnan(b.telemetry[0].position));
  for (int t = 0; t < 40; ++t) static_cast<void>(b.tick());
  EXPECT_TRUE(b.telemetry[1].faults & kDeviceLost);
  EXPECT_FALSE(b.telemetry[0].faults & kDeviceLost);
}

TEST(OdriveDrives, AnAxisErrorIsFaultStateWithItsNamedCause) {
  OdriveBench b({{1, 0.0}, {2, 0.0}});
  ASSERT_EQ(b.drives->start(*b.bus), Status::ok) << b.drives->start_problem();
  for (int t = 0; t < 5; ++t) ASSERT_EQ(b.tick(), Status::ok);
  b.axes[1]->inject_axis_error(od::kMotorFailed);
  for (int t = 0; t < 11; ++t) ASSERT_EQ(b.tick(), Status::ok);
  EXPECT_EQ(b.telemetry[1].faults, kDeviceFaultState | kDeviceElectrical);
  EXPECT_EQ(b.telemetry[0].faults, 0u);
  EXPECT_EQ(b.drives->channel_problem(1), "ODrive node 2: axis error 0x40 (motor failed), state IDLE");
  EXPECT_GE(b.drives->device_errors(), 1u);
}

TEST(OdriveDrives, LeavingClosedLoopWithoutAnErrorIsFaultState) {
  OdriveBench b({{1, 0.0}});
  ASSERT_EQ(b.drives->start(*b.bus), Status::ok) << b.drives->start_problem();
  b.axes[0]->receive(od::encode_set_axis_state(1, od::AxisState::idle));  // someone else's tool
  for (int t = 0; t < 11; ++t) ASSERT_EQ(b.tick(), Status::ok);
  EXPECT_EQ(b.telemetry[0].faults, kDeviceFaultState);
  EXPECT_EQ(b.drives->channel_problem(0), "ODrive node 1: state IDLE, not CLOSED_LOOP_CONTROL");
  EXPECT_EQ(b.drives->device_errors(), 0u);
}

TEST(OdriveDrives, ReleaseIdlesTheAxes) {
  OdriveBench b({{1, 0.0}, {2, 0.0}, {3, 0.0}});
  ASSERT_EQ(b.drives->start(*b.bus), Status::ok) << b.drives->start_problem();
  ASSERT_EQ(b.tick(), Status::ok);
  b.drives->release_channel(1);
  const std::size_t mark = b.bus->sent.size();
  for (int t = 0; t < 12; ++t) ASSERT_EQ(b.tick(), Status::ok);
  const std::vector<CanFrame> node2 = b.sent_to(2, mark);
  ASSERT_EQ(node2.size(), 1u);  // IDLE once, then nothing: no positions, no requests
  EXPECT_EQ(node2[0], od::encode_set_axis_state(2, od::AxisState::idle));
  EXPECT_EQ(b.axes[1]->state(), kOdriveIdle);
  EXPECT_EQ(b.axes[0]->state(), kOdriveClosedLoop);
  EXPECT_EQ(b.telemetry[1].faults, 0u);  // idle is what a released axis should be
  EXPECT_TRUE(std::isnan(b.telemetry[1].position));

  b.out->clear();
  b.drives->encode_release(*b.out);
  ASSERT_EQ(b.out->size(), 3u);
  EXPECT_EQ(b.bus->send(b.out->frames()), Status::ok);
  for (const auto& axis : b.axes) EXPECT_EQ(axis->state(), kOdriveIdle);
  for (int t = 0; t < 11; ++t) ASSERT_EQ(b.tick(), Status::ok);
  EXPECT_EQ(b.out->size(), 0u);  // every axis was told: nothing more to send
  for (const auto& t : b.telemetry) EXPECT_EQ(t.faults, 0u);
}

/// A node that puts junk on the bus every millisecond: other nodes' heartbeats, malformed
/// frames on the drives' own ids, extended and remote frames.
class OdriveNoiseNode final : public sim::CanNode {
 public:
  void receive(const CanFrame&) override {}
  bool peek_transmit(CanFrame* f) const override {
    if (pending_.empty()) return false;
    *f = pending_.front();
    return true;
  }
  void pop_transmit() override { pending_.pop_front(); }
  void advance(double) override {
    const std::vector<std::uint8_t> short_bytes{0x40, 0, 0}, idle_error{0x40, 0, 0, 0, 1, 0, 0, 0};
    pending_.push_back(can_data_frame(od::can_id(9, od::kHeartbeat), idle_error));   // not ours
    pending_.push_back(can_data_frame(od::can_id(1, od::kHeartbeat), short_bytes));  // ours, malformed
    pending_.push_back(can_data_frame(od::can_id(1, od::kGetEncoderEstimates), short_bytes));
    pending_.push_back(can_data_frame(od::can_id(1, od::kHeartbeat), idle_error, true));  // extended id
    pending_.push_back(can_remote_frame(od::can_id(1, od::kHeartbeat), 8));
    pending_.push_back(can_data_frame(0x700, short_bytes));  // CANopen heartbeat range
  }

 private:
  std::deque<CanFrame> pending_;
};

TEST(OdriveDrives, UnknownAndMalformedFramesAreIgnored) {
  OdriveNoiseNode noise;
  sim::SimOdriveAxisConfig c;
  c.node = 1;
  c.initial_position_turns = 0.25;
  sim::SimOdriveAxis axis(c);
  test::DirectCanBus bus({&axis, &noise});
  OdriveDrivesConfig config;
  config.actuators.push_back({0, 1, odrive_degrees(), 4, 20, od::InputMode::passthrough});
  OdriveDrives drives(config);
  ASSERT_EQ(drives.start(bus), Status::ok) << drives.start_problem();
  CanOutbox out(drives.max_tick_frames());
  std::vector<double> frame{90};
  std::vector<ChannelTelemetry> telemetry(1);
  for (int t = 0; t < 40; ++t) {
    out.clear();
    drives.encode_tick(frame, out);
    ASSERT_EQ(bus.send(out.frames()), Status::ok);
    CanFrame f;
    while (bus.receive(&f, bus.now()) == Status::ok) static_cast<void>(drives.take(f));
    ASSERT_EQ(drives.settle(), Status::ok);
    bus.advance(kOdriveTick);
  }
  drives.read_telemetry(telemetry);
  EXPECT_EQ(telemetry[0].faults, 0u);
  EXPECT_NEAR(telemetry[0].position, 90, 0.5);
  EXPECT_EQ(drives.device_errors(), 0u);

  // Frame by frame.
  const std::vector<std::uint8_t> closed{0, 0, 0, 0, 8, 0, 0, 0};
  EXPECT_TRUE(drives.take(can_data_frame(od::can_id(1, od::kHeartbeat), closed)));
  EXPECT_FALSE(drives.take(can_data_frame(od::can_id(9, od::kHeartbeat), closed)));
  EXPECT_FALSE(drives.take(can_data_frame(od::can_id(1, od::kHeartbeat), closed, true)));
  EXPECT_FALSE(drives.take(can_remote_frame(od::can_id(1, od::kGetEncoderEstimates), 8)));
  EXPECT_FALSE(drives.take(od::encode_set_input_pos(1, 0.5f)));  // our own command, echoed
  CanFrame error_frame;
  error_frame.error = true;
  error_frame.id = kCanErrorProtocol;
  EXPECT_FALSE(drives.take(error_frame));
  const std::vector<std::uint8_t> nan_position{0x00, 0x00, 0xC0, 0x7F, 0, 0, 0, 0};
  EXPECT_FALSE(drives.take(can_data_frame(od::can_id(1, od::kGetEncoderEstimates), nan_position)));
}

TEST(OdriveDrives, StartNamesAMissingAxis) {
  OdriveDrivesConfig config;
  config.actuators.push_back({0, 1, odrive_degrees(), 4, 20, od::InputMode::passthrough});
  config.actuators.push_back({1, 5, odrive_degrees(), 4, 20, od::InputMode::passthrough});
  OdriveBench b({{1, 0.0}}, config);
  EXPECT_EQ(b.drives->start(*b.bus), Status::timeout);
  EXPECT_EQ(b.drives->start_problem(),
            "ODrive node 5: no encoder estimate in answer to Get Encoder Estimates within 100 ms (timeout)");
  EXPECT_EQ(b.axes[0]->state(), kOdriveIdle);  // the axis already started was idled again
}

TEST(OdriveDrives, StartNamesARefusedAxisAndWhatItsHeartbeatSaid) {
  OdriveBench b({{1, 0.0}, {2, 0.0}}, {}, [](sim::SimOdriveAxisConfig& c) { c.calibrated = c.node != 2; });
  EXPECT_EQ(b.drives->start(*b.bus), Status::bad_data);
  EXPECT_EQ(b.drives->start_problem(),
            "ODrive node 2: did not enter CLOSED_LOOP_CONTROL; its heartbeat said: axis error 0x1 (invalid state), state IDLE");
  EXPECT_EQ(b.axes[0]->state(), kOdriveIdle);
  EXPECT_LT(b.bus->now(), 500ms);  // refused: no need to wait out the 2 s timeout
}

TEST(OdriveDrives, StartWaitsForASlowAxisUpToItsTimeout) {
  OdriveDrivesConfig config;
  config.closed_loop_timeout = 1000ms;
  OdriveBench slow({{1, 0.0}}, config, [](sim::SimOdriveAxisConfig& c) { c.closed_loop_entry_s = 1.5; });
  EXPECT_EQ(slow.drives->start(*slow.bus), Status::timeout);
  EXPECT_EQ(
      slow.drives->start_problem(),
      "ODrive node 1: did not enter CLOSED_LOOP_CONTROL within 1000 ms; its last heartbeat said: axis error 0x0, state IDLE");

  OdriveBench silent({{1, 0.0}}, config, [](sim::SimOdriveAxisConfig& c) { c.heartbeat_period_s = 0; });
  EXPECT_EQ(silent.drives->start(*silent.bus), Status::timeout);
  EXPECT_EQ(silent.drives->start_problem(), "ODrive node 1: did not enter CLOSED_LOOP_CONTROL: no heartbeat within 1000 ms");

  OdriveBench patient({{1, 0.0}}, {}, [](sim::SimOdriveAxisConfig& c) { c.closed_loop_entry_s = 1.5; });
  EXPECT_EQ(patient.drives->start(*patient.bus), Status::ok) << patient.drives->start_problem();
}

TEST(OdriveDrives, StartSetsTheInputModeAndClearsOldErrors) {
  OdriveDrivesConfig config;
  config.actuators.push_back({0, 1, odrive_degrees(), 4, 20, od::InputMode::trap_traj});
  OdriveBench b({{1, 0.0}}, config);
  b.axes[0]->inject_axis_error(od::kEstopRequested);
  ASSERT_EQ(b.drives->start(*b.bus), Status::ok) << b.drives->start_problem();
  EXPECT_EQ(b.axes[0]->input_mode(), static_cast<int>(od::InputMode::trap_traj));
  EXPECT_EQ(b.axes[0]->axis_error(), 0u);
  EXPECT_EQ(b.axes[0]->state(), kOdriveClosedLoop);
}

TEST(OdriveDrives, ReadbackNoneSendsOnlyPositions) {
  OdriveDrivesConfig config;
  config.readback = OdriveReadback::none;
  OdriveBench b({{1, 0.0}, {2, 0.0}}, config);
  ASSERT_EQ(b.drives->start(*b.bus), Status::ok) << b.drives->start_problem();
  EXPECT_EQ(b.drives->max_tick_frames(), 2u);
  const std::size_t mark = b.bus->sent.size();
  for (int t = 0; t < 12; ++t) ASSERT_EQ(b.tick(), Status::ok);
  for (std::size_t k = mark; k < b.bus->sent.size(); ++k) EXPECT_EQ(od::odrive_command(b.bus->sent[k].id), od::kSetInputPos);
  EXPECT_TRUE(b.drives->replies_complete());
  EXPECT_TRUE(std::isnan(b.telemetry[0].position));
  EXPECT_EQ(b.telemetry[0].faults, 0u);  // heartbeats are still watched
}

TEST(OdriveDrives, HeartbeatLayout06) {
  OdriveDrivesConfig config;
  config.heartbeat_layout = od::HeartbeatLayout::v0_6;
  OdriveBench b({{1, 0.0}}, config, [](sim::SimOdriveAxisConfig& c) { c.heartbeat_layout = od::HeartbeatLayout::v0_6; });
  ASSERT_EQ(b.drives->start(*b.bus), Status::ok) << b.drives->start_problem();
  b.axes[0]->inject_axis_error(0x40);
  for (int t = 0; t < 11; ++t) ASSERT_EQ(b.tick(), Status::ok);
  EXPECT_EQ(b.telemetry[0].faults, kDeviceFaultState | kDeviceOther);  // 0.6 bits are not named here
  EXPECT_EQ(b.drives->channel_problem(0), "ODrive node 1: axis error 0x40, state IDLE");
}

TEST(OdriveDrives, ConfigIsChecked) {
  auto make = [](auto edit) {
    OdriveDrivesConfig c;
    c.actuators.push_back({0, 1, odrive_degrees(), 4, 20, od::InputMode::passthrough});
    c.actuators.push_back({1, 2, odrive_degrees(), 4, 20, od::InputMode::passthrough});
    edit(c);
    OdriveDrives d(c);
  };
  EXPECT_NO_THROW(make([](OdriveDrivesConfig&) {}));
  EXPECT_THROW(make([](OdriveDrivesConfig& c) { c.actuators[1].node = 1; }), std::invalid_argument);
  EXPECT_THROW(make([](OdriveDrivesConfig& c) { c.actuators[1].node = 64; }), std::invalid_argument);
  EXPECT_THROW(make([](OdriveDrivesConfig& c) { c.actuators[0].velocity_limit = 0; }), std::invalid_argument);
  EXPECT_THROW(make([](OdriveDrivesConfig& c) { c.actuators[0].current_limit = NAN; }), std::invalid_argument);
  EXPECT_THROW(make([](OdriveDrivesConfig& c) { c.actuators[0].input_mode = od::InputMode::vel_ramp; }), std::invalid_argument);
  EXPECT_THROW(make([](OdriveDrivesConfig& c) { c.heartbeat_budget_ticks = 0; }), std::invalid_argument);
}

TEST(OdriveDrives, WithTheTickKnownEachSetInputPosCarriesTheMotionsVelocity) {
  OdriveDrivesConfig config;
  config.tick_period_s = std::chrono::duration<double>(kOdriveTick).count();
  OdriveBench b({{1, 0.0}}, config);
  ASSERT_EQ(b.drives->start(*b.bus), Status::ok) << b.drives->start_problem();
  // From 0 to 36° (0.1 turn) in one tick: 10 turns/s; then holding: 0.
  std::vector<od::InputPos> sent;
  for (double degrees : {36.0, 36.0}) {
    b.frame[0] = degrees;
    const std::size_t from = b.bus->sent.size();
    ASSERT_EQ(b.tick(), Status::ok);
    for (const CanFrame& f : b.sent_to(1, from))
      if (od::InputPos p; od::decode_set_input_pos(f, &p)) sent.push_back(p);
  }
  ASSERT_EQ(sent.size(), 2u);
  EXPECT_NEAR(sent[0].position, 0.1, 1e-6);
  EXPECT_NEAR(sent[0].vel_ff, 10.0, 1e-3);
  EXPECT_NEAR(sent[1].vel_ff, 0.0, 1e-3);
}

}  // namespace
}  // namespace avar::firmware_iface
