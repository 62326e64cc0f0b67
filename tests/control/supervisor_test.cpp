// The supervisor: every fault from every state takes the one path to the safe state, with each
// actuator's fail-safe action, stays latched, and is cleared only by reset().
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <vector>

#include "avar/control/controller.hpp"
#include "avar/control/runner.hpp"
#include "../support/recording_link.hpp"
#include "../support/rig_names.hpp"

namespace avar::control {
namespace {

using testing::RecordingLink;

/// Three channels, one per fail-safe action: hold, rest, release.
Rig rig() {
  Rig r;
  r.name = "failsafe";
  for (const char* name : {"held", "rested", "released"})
    r.channels.push_back({.name = name, .unit = "deg", .min = -50, .max = 50, .rest = 0, .max_velocity = 200,
                          .max_acceleration = 4000, .max_jerk = 100000, .ramp_velocity = 50, .tracking_tolerance = 5,
                          .where = {}});
  r.links.emplace_back().name = "bus";
  const Failsafe actions[] = {Failsafe::hold, Failsafe::rest, Failsafe::release};
  for (std::size_t c = 0; c < 3; ++c) {
    ActuatorSpec a;
    a.channel = rig::ChannelIndex{c};
    a.device_channel = static_cast<int>(c);
    a.failsafe = actions[c];
    r.actuators.push_back(a);
  }
  return r;
}

playback::Show show() {
  playback::Show s;
  s.name = "ramp";
  s.duration = 2;
  for (const char* name : {"held", "rested", "released"}) {
    playback::RawCurve raw;
    playback::RawKey a, b;
    a.time = 0, a.value = 0, b.time = 1, b.value = 40;
    raw.keys = {a, b};
    playback::Curve curve = playback::Curve::build(raw);
    s.tracks.push_back({name, raw, std::move(curve), {}});
  }
  return s;
}

constexpr double kDt = 0.01;

/// Ticks until the controller reaches `state` (or gives up); returns the loop time reached.
double drive_to(Controller& c, Phase state, int& k) {
  if (state == Phase::disabled) return 0;
  c.begin(0, std::vector<double>{0, 0, 0});
  for (; c.phase() != state && k < 1000; ++k) {
    if (state == Phase::stopping && c.phase() == Phase::running && c.show_time() > 1.5) c.request_stop(k * kDt);
    c.tick(k * kDt);
  }
  // Move on a little inside the state, so that the figure is away from rest.
  for (int i = 0; i < 5 && c.phase() == state; ++i, ++k) c.tick(k * kDt);
  return k * kDt;
}

const FaultCause kCauses[] = {FaultCause::estop,           FaultCause::link_watchdog, FaultCause::link_failure,
                              FaultCause::tracking_error,  FaultCause::non_finite,    FaultCause::device_overheat,
                              FaultCause::device_overload, FaultCause::device_error,  FaultCause::device_lost,
                              FaultCause::deadline_budget};
const Phase kStates[] = {Phase::disabled, Phase::homing, Phase::running, Phase::stopping};

TEST(Supervisor, EveryFaultFromEveryStateTakesTheFailsafePathAndLatches) {
  const Rig r = rig();
  const playback::Show s = show();
  for (Phase state : kStates) {
    for (FaultCause cause : kCauses) {
      SCOPED_TRACE(std::string(to_string(cause)) + " while " + to_string(state));
      RecordingLink link;
      Controller c(r, s, {&link}, {.tick_period_s = kDt});
      int k = 0;
      const double t = drive_to(c, state, k);
      ASSERT_EQ(c.phase(), state);
      const std::size_t sent_before = link.frames.size();
      const double held_heading = c.limiter().heading(0);
      c.fault(cause, 1, 7.5, t);
      EXPECT_EQ(c.phase(), Phase::faulted);
      EXPECT_EQ(c.latched_fault().cause, cause);
      EXPECT_EQ(c.latched_fault().from, state);
      EXPECT_EQ(c.latched_fault().index, 1u);
      EXPECT_DOUBLE_EQ(c.latched_fault().value, 7.5);
      // A second fault is counted but the first stays latched.
      c.fault(FaultCause::estop, 0, 0, t);
      EXPECT_EQ(c.latched_fault().cause, cause);
      EXPECT_EQ(c.faults_seen(), 2u);

      if (state == Phase::disabled) {
        // Nothing was moving: nothing starts moving, and the fault can be cleared at once.
        EXPECT_FALSE(c.active());
        c.tick(t);
        EXPECT_EQ(link.frames.size(), sent_before);
        EXPECT_TRUE(link.released_channels.empty());
        EXPECT_TRUE(c.reset());
        EXPECT_EQ(c.phase(), Phase::disabled);
        continue;
      }
      EXPECT_EQ(link.released_channels, std::vector<std::size_t>{2});  // only the "release" channel
      EXPECT_TRUE(c.active());
      EXPECT_FALSE(c.reset());  // not while the fail-safe motions run
      for (; c.active() && k < 5000; ++k) c.tick(k * kDt);
      EXPECT_FALSE(c.active());
      const std::vector<double>& last = link.frames.back();
      EXPECT_NEAR(last[0], held_heading, 1e-9);  // hold: stays where it was heading
      EXPECT_DOUBLE_EQ(last[1], 0.0);            // rest: eased to rest
      EXPECT_EQ(c.phase(), Phase::faulted);      // still latched
      EXPECT_TRUE(c.reset());
      EXPECT_EQ(c.phase(), Phase::disabled);
      EXPECT_EQ(c.latched_fault().cause, FaultCause::none);
    }
  }
}

TEST(Supervisor, AFaultDuringTheSoftStartHoldsWhereBrakingStopsTheChannel) {
  // Homing from -30 to the show's first frame, 0: the glide's goal is not a pose to hold.
  const Rig r = rig();
  const playback::Show s = show();
  RecordingLink link;
  Controller c(r, s, {&link}, {.tick_period_s = kDt});
  c.begin(0, std::vector<double>{-30, -30, -30});
  int k = 0;
  for (; k < 50; ++k) c.tick(k * kDt);
  ASSERT_EQ(c.phase(), Phase::homing);
  const double at_fault = link.frames.back()[0];
  const double braked = c.limiter().heading(0);
  ASSERT_GT(at_fault, -29.0);
  c.fault(FaultCause::estop, 0, 0, k * kDt);
  for (; c.active() && k < 5000; ++k) c.tick(k * kDt);
  const std::vector<double>& last = link.frames.back();
  // Held where braking at its limits stops it: a little on (from up to 50/s at 4000/s²), far
  // from the first frame.
  EXPECT_NEAR(last[0], braked, 1e-9);
  EXPECT_GT(last[0], at_fault);
  EXPECT_LT(last[0], at_fault + 1.5);
  EXPECT_DOUBLE_EQ(last[1], 0.0);  // rest: eased to rest
}

TEST(Supervisor, TrackingErrorBeyondToleranceFaultsWithTheChannelAndError) {
  const Rig r = rig();
  const playback::Show s = show();
  RecordingLink link;
  Controller c(r, s, {&link}, {.tick_period_s = kDt});
  int k = 0;
  drive_to(c, Phase::running, k);
  std::vector<double> measured(c.commanded().begin(), c.commanded().end());
  measured[1] += 4.0;  // within the 5-degree tolerance
  const bool known[3] = {true, true, false};
  c.feed_back(measured, known);
  c.tick(k++ * kDt);
  EXPECT_EQ(c.phase(), Phase::running);
  measured.assign(c.commanded().begin(), c.commanded().end());
  measured[1] -= 6.0;
  c.feed_back(measured, known);
  c.tick(k * kDt);
  EXPECT_EQ(c.latched_fault().cause, FaultCause::tracking_error);
  EXPECT_EQ(c.latched_fault().index, 1u);
  EXPECT_NEAR(c.latched_fault().value, 6.0, 1e-9);
}

TEST(Supervisor, DeviceTelemetryFaultsLatchWithTheirChannelAndFeedTracking) {
  using firmware_iface::ChannelTelemetry;
  const Rig r = rig();
  const playback::Show s = show();
  struct Case {
    std::uint32_t bits;
    FaultCause cause;
    double value;
  };
  for (const Case& expected :
       {Case{firmware_iface::kDeviceOverheat, FaultCause::device_overheat, 81},
        Case{firmware_iface::kDeviceOverload, FaultCause::device_overload, 0.97},
        Case{firmware_iface::kDeviceEncoder, FaultCause::device_error, static_cast<double>(firmware_iface::kDeviceEncoder)},
        Case{firmware_iface::kDeviceFaultState, FaultCause::device_error,
             static_cast<double>(firmware_iface::kDeviceFaultState)}}) {
    SCOPED_TRACE(to_string(expected.cause));
    RecordingLink link;
    Controller c(r, s, {&link}, {.tick_period_s = kDt});
    int k = 0;
    drive_to(c, Phase::running, k);
    std::vector<ChannelTelemetry> telemetry(3);
    // Fresh, healthy telemetry close to the command: no fault.
    for (std::size_t ch = 0; ch < 3; ++ch) {
      telemetry[ch].position = c.commanded()[ch];
      telemetry[ch].temperature_c = 40;
      telemetry[ch].load = 0.2;
      telemetry[ch].updates = 1;
    }
    c.feed_telemetry(telemetry);
    c.tick(k++ * kDt);
    EXPECT_EQ(c.phase(), Phase::running);
    // The same (stale) entry again with fault bits set: not fresh, ignored.
    telemetry[2].faults = expected.bits;
    c.feed_telemetry(telemetry);
    c.tick(k++ * kDt);
    EXPECT_EQ(c.phase(), Phase::running);
    // Fresh: latched, on its channel.
    telemetry[2].updates = 2;
    telemetry[2].temperature_c = 81;
    telemetry[2].load = 0.97;
    c.feed_telemetry(telemetry);
    EXPECT_EQ(c.phase(), Phase::faulted);
    EXPECT_EQ(c.latched_fault().cause, expected.cause);
    EXPECT_EQ(c.latched_fault().index, 2u);
    EXPECT_DOUBLE_EQ(c.latched_fault().value, expected.value);
  }
  // Positions from telemetry reach the tracking check.
  RecordingLink link;
  Controller c(r, s, {&link}, {.tick_period_s = kDt});
  int k = 0;
  drive_to(c, Phase::running, k);
  std::vector<ChannelTelemetry> telemetry(3);
  telemetry[0].position = c.commanded()[0] + 6;
  telemetry[0].updates = 1;
  c.feed_telemetry(telemetry);
  c.tick(k * kDt);
  EXPECT_EQ(c.latched_fault().cause, FaultCause::tracking_error);
  EXPECT_EQ(c.latched_fault().index, 0u);
}

TEST(Supervisor, ALostDeviceFaultsWithoutFreshTelemetry) {
  // A device that stopped answering refreshes nothing; its link flags the silence.
  const Rig r = rig();
  const playback::Show s = show();
  RecordingLink link;
  Controller c(r, s, {&link}, {.tick_period_s = kDt});
  int k = 0;
  drive_to(c, Phase::running, k);
  std::vector<firmware_iface::ChannelTelemetry> telemetry(3);
  c.feed_telemetry(telemetry);
  c.tick(k++ * kDt);
  EXPECT_EQ(c.phase(), Phase::running);
  telemetry[1].faults = firmware_iface::kDeviceLost;
  c.feed_telemetry(telemetry);
  EXPECT_EQ(c.phase(), Phase::faulted);
  EXPECT_EQ(c.latched_fault().cause, FaultCause::device_lost);
  EXPECT_EQ(c.latched_fault().index, 1u);
}

TEST(Supervisor, EstopInputReachesTheControllerThroughTheRunner) {
  const Rig r = rig();
  const playback::Show s = show();
  class Pressing final : public TickObserver {
   public:
    explicit Pressing(std::atomic<bool>& estop) : estop_(estop) {}
    void after_tick(std::uint64_t tick, double, double, double, Controller&) override {
      if (tick == 60) estop_.store(true);
    }

   private:
    std::atomic<bool>& estop_;
  };
  RecordingLink link;
  Controller c(r, s, {&link}, {.tick_period_s = kDt});
  c.begin(0, std::vector<double>{0, 0, 0});
  std::atomic<bool> estop{false};
  Pressing pressing(estop);
  const std::atomic<int> no_interrupts{0};
  RunOptions options{1 / kDt, ClockMode::stepped, {}};
  options.estop = &estop;
  EXPECT_FALSE(run_loop(c, options, pressing, no_interrupts).interrupted);
  EXPECT_EQ(c.latched_fault().cause, FaultCause::estop);
  EXPECT_NEAR(c.latched_fault().time_s, 0.61, 1e-9);
  EXPECT_DOUBLE_EQ(link.frames.back()[1], 0.0);
}

}  // namespace
}  // namespace avar::control
