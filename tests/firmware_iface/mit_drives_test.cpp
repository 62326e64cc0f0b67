// MitDrives end to end against simulated MIT-mode motors over a direct CAN bus: start without a
// jump, tracking, silence, release, saturation, and the config checks.
#include "avar/firmware_iface/mit_drives.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "../support/direct_can_bus.hpp"
#include "avar/sim/sim_mit_motor.hpp"

namespace avar::firmware_iface {
namespace {

using sim::SimMitMotor;
using sim::SimMitMotorConfig;
using test::DirectCanBus;

constexpr double kMitTick_s = 0.005;  // a 200 Hz loop
// Channel -90..90 (degrees of a joint) -> -1.5..1.5 rad at the motor.
constexpr LinearCalibration kMitCalibration{-90, 90, -1.5, 1.5};

SimMitMotorConfig mit_motor_at(std::uint32_t id, double position) {
  SimMitMotorConfig c;
  c.id = id;
  c.initial_position = position;
  return c;
}

MitDrivesConfig mit_two_motors() {
  MitDrivesConfig c;
  c.actuators.push_back({.channel = 0, .node = 1, .kp = 20, .kd = 0.5, .calibration = kMitCalibration});
  c.actuators.push_back({.channel = 1, .node = 2, .kp = 20, .kd = 0.5, .calibration = kMitCalibration});
  c.reply_budget_ticks = 4;
  return c;
}

/// Two simulated motors, the bus, the drive set, and one tick as a CAN link runs it.
struct MitBench {
  explicit MitBench(double p1 = 0, double p2 = 0, MitDrivesConfig config = mit_two_motors())
      : m1(mit_motor_at(1, p1)),
        m2(mit_motor_at(2, p2)),
        bus({&m1, &m2}),
        drives(std::move(config)),
        out(drives.max_tick_frames()) {}

  Status tick(std::span<const double> frame) {
    const auto start = bus.now();
    out.clear();
    drives.encode_tick(frame, out);
    EXPECT_EQ(bus.send(out.frames()), Status::ok);
    CanFrame f;
    const auto deadline = bus.now() + std::chrono::milliseconds(1);
    while (!drives.replies_complete() && bus.receive(&f, deadline) == Status::ok) drives.take(f);
    // As CanLink: what has already come is taken too (a motor no longer waited for).
    while (bus.receive(&f, bus.now()) == Status::ok) drives.take(f);
    const Status s = drives.settle();
    const auto end = start + std::chrono::microseconds(static_cast<long>(kMitTick_s * 1e6));
    if (end > bus.now()) bus.advance(end - bus.now());
    return s;
  }
  ChannelTelemetry telemetry(std::size_t channel) const {
    std::vector<ChannelTelemetry> t(2);
    drives.read_telemetry(t);
    return t[channel];
  }
  std::size_t sent_exits(std::uint32_t node) const {
    std::size_t n = 0;
    for (const CanFrame& f : bus.sent)
      if (f.id == node && f.dlc == 8 &&
          mit::classify(std::span<const std::uint8_t, 8>(f.data.data(), 8)) == mit::MitFrameKind::exit_motor_mode)
        ++n;
    return n;
  }

  SimMitMotor m1, m2;
  DirectCanBus bus;
  MitDrives drives;
  CanOutbox out;
};

const double kMitQuantum = 25.0 / 65535;  // rad, one position step of ±12.5

TEST(MitDrives, StartEntersMotorModeAtThePresentPositionWithoutAJump) {
  MitBench b(0.7, -0.3);
  ASSERT_EQ(b.drives.start(b.bus), Status::ok) << b.drives.start_problem();
  EXPECT_TRUE(b.m1.motor_mode());
  EXPECT_TRUE(b.m2.motor_mode());
  // Motor 1: enter motor mode (K6), then a command at the position its reply gave.
  ASSERT_GE(b.bus.sent.size(), 4u);
  EXPECT_EQ(b.bus.sent[0], mit::special_frame(1, mit::MitFrameKind::enter_motor_mode));
  EXPECT_EQ(b.bus.sent[1].id, 1u);
  EXPECT_NEAR(b.m1.command().position, 0.7, 2 * kMitQuantum);
  EXPECT_NEAR(b.m1.command().kp, 20, 0.2);
  EXPECT_NEAR(b.m2.command().position, -0.3, 2 * kMitQuantum);
  for (int i = 0; i < 40; ++i) {
    b.bus.advance(std::chrono::milliseconds(5));
    EXPECT_NEAR(b.m1.position(), 0.7, 3 * kMitQuantum);
    EXPECT_NEAR(b.m2.position(), -0.3, 3 * kMitQuantum);
  }
  // 60 channel units per rad; the encoder step and the reply's quantum are each 0.0004 rad.
  EXPECT_NEAR(b.telemetry(0).position, 0.7 * 60, 0.05);
  EXPECT_NEAR(b.telemetry(1).position, -0.3 * 60, 0.05);
  EXPECT_EQ(b.telemetry(0).updates, 1u);
}

TEST(MitDrives, TheFirstTickFromTheReadPositionsDoesNotJump) {
  MitBench b(0.4, 0.0);
  ASSERT_EQ(b.drives.start(b.bus), Status::ok);
  std::vector<double> frame(2, 0.0);
  bool known[2] = {false, false};
  ASSERT_EQ(b.drives.read_positions(b.bus, frame, known), Status::ok);
  EXPECT_TRUE(known[0] && known[1]);
  EXPECT_NEAR(frame[0], 0.4 * 60, 0.05);
  for (int i = 0; i < 20; ++i) {
    ASSERT_EQ(b.tick(frame), Status::ok);
    EXPECT_NEAR(b.m1.position(), 0.4, 3 * kMitQuantum);
  }
}

TEST(MitDrives, ReadPositionsBeforeStartLeavesTheMotorsInMenuMode) {
  MitBench b(0.2, -0.1);
  std::vector<double> frame(2, 0.0);
  bool known[2] = {false, false};
  ASSERT_EQ(b.drives.read_positions(b.bus, frame, known), Status::ok);
  EXPECT_NEAR(frame[0], 0.2 * 60, 0.05);
  EXPECT_NEAR(frame[1], -0.1 * 60, 0.05);
  EXPECT_FALSE(b.m1.motor_mode());
  EXPECT_FALSE(b.m2.motor_mode());
}

TEST(MitDrives, AMotorThatDoesNotAnswerFailsTheStartByName) {
  MitBench b;
  b.bus.set_attached(&b.m2, false);
  EXPECT_EQ(b.drives.start(b.bus), Status::timeout);
  EXPECT_EQ(b.drives.start_problem(), "MIT motor 2: no reply to enter motor mode within 50 ms");
  EXPECT_FALSE(b.m1.motor_mode());  // the one already up is told to exit motor mode
}

TEST(MitDrives, AMotorOutsideItsCalibratedWindowIsNotStarted) {
  MitBench b(2.0, 0);
  EXPECT_EQ(b.drives.start(b.bus), Status::out_of_range);
  EXPECT_EQ(b.drives.start_problem(), "MIT motor 1: at 2.000 rad, outside its calibrated window -1.500..1.500 rad");
  EXPECT_FALSE(b.m1.motor_mode());
  EXPECT_FALSE(b.m1.driving());
}

TEST(MitDrives, AStreamedRampIsTrackedWithinTheStatedLag) {
  MitBench b;
  ASSERT_EQ(b.drives.start(b.bus), Status::ok);
  // 1 rad/s for 1 s (60 channel units/s). With v = 0 in every command the damping lags the ramp
  // by kd·w/kp = 0.025 rad, plus up to one tick of the ramp (0.005 rad) and the quantisation.
  const double w = 1.0, lag = 0.5 * w / 20;
  std::vector<double> frame(2, 0.0);
  double worst = 0;
  for (int i = 1; i <= 200; ++i) {
    const double target = w * i * kMitTick_s;
    frame[0] = target * 60;
    frame[1] = -target * 60;
    ASSERT_EQ(b.tick(frame), Status::ok);
    if (i > 40) {  // after the start of the ramp has settled
      worst = std::max(worst, std::abs(b.m1.position() - target));
      worst = std::max(worst, std::abs(b.m2.position() + target));
    }
  }
  EXPECT_LT(worst, lag + w * kMitTick_s + 0.005);
  EXPECT_NEAR(b.telemetry(0).position, b.m1.position() * 60, 0.5);
  EXPECT_EQ(b.telemetry(0).updates, 201u);
  EXPECT_EQ(b.telemetry(0).faults, 0u);
}

TEST(MitDrives, AMotorThatStopsAnsweringIsLostWithinTheBudget) {
  MitBench b;
  ASSERT_EQ(b.drives.start(b.bus), Status::ok);
  std::vector<double> frame(2, 0.0);
  ASSERT_EQ(b.tick(frame), Status::ok);
  b.m2.set_answering(false);
  for (int i = 1; i <= 4; ++i) {
    EXPECT_EQ(b.tick(frame), Status::timeout);
    EXPECT_TRUE(std::isnan(b.telemetry(1).position));  // stale feedback is absent
    EXPECT_EQ(b.telemetry(1).faults & kDeviceLost, i < 4 ? 0u : std::uint32_t{kDeviceLost}) << "tick " << i;
    EXPECT_EQ(b.telemetry(0).faults, 0u);
    EXPECT_FALSE(std::isnan(b.telemetry(0).position));
  }
  EXPECT_EQ(b.drives.channel_problem(1), "MIT motor 2: no reply for 4 ticks");
  EXPECT_EQ(b.drives.channel_problem(0), "");
  b.m2.set_answering(true);
  EXPECT_EQ(b.tick(frame), Status::ok);
  EXPECT_EQ(b.telemetry(1).faults, 0u);
  EXPECT_EQ(b.drives.channel_problem(1), "");
}

TEST(MitDrives, ReleasingAChannelSendsExitMotorModeOnce) {
  MitBench b(0.1, 0.1);
  ASSERT_EQ(b.drives.start(b.bus), Status::ok);
  std::vector<double> frame(2, 6.0);
  ASSERT_EQ(b.tick(frame), Status::ok);
  b.drives.release_channel(0);
  for (int i = 0; i < 5; ++i) ASSERT_EQ(b.tick(frame), Status::ok);
  EXPECT_EQ(b.sent_exits(1), 1u);
  EXPECT_EQ(b.sent_exits(2), 0u);
  EXPECT_FALSE(b.m1.motor_mode());  // limp
  EXPECT_TRUE(b.m2.driving());
  EXPECT_TRUE(std::isnan(b.telemetry(0).position));  // no longer asked
  EXPECT_EQ(b.telemetry(0).faults, 0u);              // and not lost
  b.out.clear();
  b.drives.encode_release(b.out);
  EXPECT_EQ(b.out.size(), 2u);
  ASSERT_EQ(b.bus.send(b.out.frames()), Status::ok);
  EXPECT_FALSE(b.m2.motor_mode());
  EXPECT_EQ(b.sent_exits(1), 2u);
  EXPECT_EQ(b.sent_exits(2), 1u);
  b.out.clear();
  b.drives.encode_tick(frame, b.out);
  EXPECT_EQ(b.out.size(), 0u);  // everything released and told
}

TEST(MitDrives, OutOfRangeChannelValuesSaturateInsideTheWindow) {
  MitBench b;
  ASSERT_EQ(b.drives.start(b.bus), Status::ok);
  const std::uint64_t before = b.drives.saturated();
  for (double v : {1e6, -1e6, 91.0, -91.0, std::nan(""), HUGE_VAL}) {
    std::vector<double> frame{v, 0.0};
    ASSERT_EQ(b.tick(frame), Status::ok);
    SCOPED_TRACE(v);
    EXPECT_GE(b.drives.last_command(0), -1.5);
    EXPECT_LE(b.drives.last_command(0), 1.5);
    // What the motor decoded: inside the window (truncation only lowers), never wrapped.
    EXPECT_GE(b.m1.command().position, -1.5 - kMitQuantum);
    EXPECT_LE(b.m1.command().position, 1.5);
    // Finite values saturate to the nearer edge; non-finite ones to the window's centre.
    if (!std::isfinite(v)) {
      EXPECT_NEAR(b.m1.command().position, 0, kMitQuantum);
    } else if (v > 0) {
      EXPECT_GT(b.m1.command().position, 1.5 - kMitQuantum);
    } else if (v < 0) {
      EXPECT_LT(b.m1.command().position, -1.5 + kMitQuantum);
    }
  }
  EXPECT_EQ(b.drives.saturated() - before, 6u);
}

TEST(MitDrives, LoadIsTheMeasuredTorqueOverTheTorqueLimit) {
  MitDrivesConfig c = mit_two_motors();
  c.actuators[0].kp = 200;
  c.actuators[0].kd = 2;
  MitBench b(0, 0, c);
  ASSERT_EQ(b.drives.start(b.bus), Status::ok);
  b.m1.model().set_external_torque(4.5);
  std::vector<double> frame(2, 0.0);
  for (int i = 0; i < 20; ++i) ASSERT_EQ(b.tick(frame), Status::ok);
  EXPECT_NEAR(b.telemetry(0).load, 4.5 / 18, 0.01);
}

TEST(MitDrives, CloneRepliesNeedTheLongerReplyFormat) {
  SimMitMotorConfig c = mit_motor_at(5, 0.3);
  c.reply_length = 8;
  SimMitMotor m(c);
  DirectCanBus bus({&m});
  MitDrivesConfig config;
  config.actuators.push_back({.channel = 0, .node = 5, .calibration = kMitCalibration});
  MitDrives tolerant(config);
  ASSERT_EQ(tolerant.start(bus), Status::ok);
  std::vector<ChannelTelemetry> t(1);
  tolerant.read_telemetry(t);
  EXPECT_NEAR(t[0].position, 18, 0.05);
  config.reply_format.accept_longer = false;
  MitDrives strict(config);
  EXPECT_EQ(strict.start(bus), Status::timeout);
  EXPECT_EQ(strict.start_problem(), "MIT motor 5: no reply to enter motor mode within 50 ms");
}

TEST(MitDrives, TakesOnlyItsOwnReplies) {
  MitBench b;
  ASSERT_EQ(b.drives.start(b.bus), Status::ok);
  std::vector<double> frame(2, 0.0);
  b.out.clear();
  b.drives.encode_tick(frame, b.out);
  EXPECT_EQ(b.out.size(), 2u);
  const auto reply = mit::pack_reply(1, 0, 0, 0, mit::kMiniCheetahRanges);
  EXPECT_FALSE(b.drives.take(can_data_frame(0x10, reply)));                  // not to the master ID
  EXPECT_FALSE(b.drives.take(can_data_frame(0, reply, /*extended=*/true)));  // extended
  EXPECT_FALSE(b.drives.take(can_data_frame(0, std::span(reply).first(5))));
  const auto other = mit::pack_reply(9, 0, 0, 0, mit::kMiniCheetahRanges);
  EXPECT_FALSE(b.drives.take(can_data_frame(0, other)));  // another motor's
  EXPECT_FALSE(b.drives.replies_complete());
  EXPECT_TRUE(b.drives.take(can_data_frame(0, reply)));
  EXPECT_FALSE(b.drives.replies_complete());
  EXPECT_TRUE(b.drives.take(can_data_frame(0, mit::pack_reply(2, 0, 0, 0, mit::kMiniCheetahRanges))));
  EXPECT_TRUE(b.drives.replies_complete());
  EXPECT_EQ(b.drives.settle(), Status::ok);
}

TEST(MitDrives, RejectsConfigsThatCannotBeDrivenSafely) {
  auto with = [](auto change) {
    MitDrivesConfig c = mit_two_motors();
    change(c);
    return c;
  };
  auto throws = [](const MitDrivesConfig& c) {
    try {
      MitDrives d(c);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  EXPECT_EQ(throws(with([](auto& c) { c.actuators[0].node = 0; })), "MIT motor 0: CAN_ID must be 1..0x7FF");
  EXPECT_EQ(throws(with([](auto& c) { c.actuators[0].node = 0x800; })), "MIT motor 2048: CAN_ID must be 1..0x7FF");
  EXPECT_EQ(throws(with([](auto& c) { c.master_id = 2; })), "MIT motor 2: CAN_ID is the master ID its replies go to");
  EXPECT_EQ(throws(with([](auto& c) { c.actuators[1].node = 1; })), "MIT motor 1 is configured twice");
  EXPECT_EQ(throws(with([](auto& c) { c.actuators[1].node = 257; })),
            "MIT motors 1 and 257 cannot be told apart: both reply with ID 1 in byte 0");
  EXPECT_EQ(throws(with([](auto& c) { c.actuators[0].kp = 600; })), "MIT motor 1: kp 600.000 is outside 0..500.000");
  EXPECT_EQ(throws(with([](auto& c) { c.actuators[0].kd = -1; })), "MIT motor 1: kd -1.000 is outside 0..5.000");
  EXPECT_EQ(throws(with([](auto& c) { c.actuators[0].calibration.device_at_max = 13; })),
            "MIT motor 1: calibrated window -1.500..13.000 rad leaves the position range -12.500..12.500 rad");
  EXPECT_EQ(throws(with([](auto& c) { c.actuators[0].ranges.kd_max = 0; })),
            "MIT motor 1: ranges need finite bounds, each min below its max, kp_max and kd_max above 0");
  EXPECT_EQ(throws(with([](auto& c) { c.reply_budget_ticks = 0; })), "MIT motors: the reply budget must be at least one tick");
  EXPECT_EQ(throws(with([](auto& c) { c.actuators[0].ranges = mit::kHt04HeaderRanges; })), "(no error)");
}

}  // namespace
}  // namespace avar::firmware_iface
