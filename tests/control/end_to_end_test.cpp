// End to end in simulated time: the controller, the real Maestro driver and the real libserial
// transport, talking over a pseudo-terminal to the simulated Maestro. Asserts what the device
// received, byte for byte where the protocol fixes it, and where the servos ended up.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>

#include "avar/control/controller.hpp"
#include "avar/control/runner.hpp"
#include "avar/firmware_iface/maestro_codec.hpp"
#include "avar/firmware_iface/maestro_link.hpp"
#include "avar/firmware_iface/serial_transport.hpp"
#include "avar/sim/pty_device_host.hpp"
#include "avar/firmware_iface/dynamixel_codec.hpp"
#include "avar/firmware_iface/dynamixel_link.hpp"
#include "avar/sim/sim_dynamixel.hpp"
#include "avar/sim/sim_maestro.hpp"
#include "avar/sim/sim_wire.hpp"
#include "../support/rig_names.hpp"

namespace avar::control {
namespace {

namespace maestro = firmware_iface::maestro;

struct Bench {
  Rig rig;
  playback::Show show;
  sim::SimMaestro device;
  sim::PtyDeviceHost host;
  firmware_iface::SerialTransport transport;
  firmware_iface::MaestroLink link;

  static sim::SimMaestroConfig device_config() {
    sim::SimMaestroConfig c;
    c.channel_count = 12;
    c.log_limit = 100000;
    c.channels[2].initial_position_us = 1700;  // the neck was left away from rest
    return c;
  }
  static firmware_iface::MaestroLinkConfig link_config(const Rig& rig) {
    firmware_iface::MaestroLinkConfig c;
    c.channel_count = 12;
    for (std::size_t i = 0; i < rig.channels.size(); ++i)
      c.actuators.push_back({i, static_cast<int>(i) + 2, {rig.channels[i].min, rig.channels[i].max, 1000, 2000, false, 0}, {}, {}});
    c.actuators[1].speed_us_per_s = 500;  // a device-side limit is sent at start
    return c;
  }
  static Rig make_rig() {
    Rig r;
    r.name = "e2e";
    r.channels.push_back({.name = "jaw", .unit = "deg", .min = 0, .max = 30, .rest = 0, .max_velocity = 200, .max_acceleration = 2000, .max_jerk = 20000, .ramp_velocity = 30, .where = {}});
    r.channels.push_back({.name = "pan", .unit = "deg", .min = -45, .max = 45, .rest = 0, .max_velocity = 300, .max_acceleration = 3000, .max_jerk = 30000, .ramp_velocity = 60, .where = {}});
    return r;
  }
  static playback::Show make_show() {
    playback::Show s;
    s.name = "e2e";
    s.duration = 1.0;
    for (const char* channel : {"jaw", "pan"}) {
      playback::RawCurve raw;
      for (auto [t, v] : {std::pair{0.0, 5.0}, {0.5, 25.0}, {1.0, 10.0}}) {
        playback::RawKey k;
        k.time = t;
        k.value = v;
        raw.keys.push_back(k);
      }
      playback::Curve c = playback::Curve::build(raw);
      s.tracks.push_back({channel, raw, std::move(c), {}});
    }
    return s;
  }

  Bench()
      : rig(make_rig()),
        show(make_show()),
        device(device_config()),
        host(device, sim::PtyDeviceHost::Clock::stepped),
        transport(host.slave_path(), 115200),
        link(transport, link_config(rig)) {}
};

/// Steps the simulated device after every tick, as `avar play` does on its simulated clock.
class StepDevice final : public TickObserver {
 public:
  explicit StepDevice(Bench& b) : b_(b) {}
  void after_tick(std::uint64_t, double, double dt, double, Controller&) override {
    ASSERT_TRUE(b_.host.wait_consumed(b_.transport.bytes_written(), std::chrono::seconds(2)));
    b_.host.with_device([&](sim::ByteDevice& d) { d.advance(dt); });
  }

 private:
  Bench& b_;
};

TEST(EndToEnd, ShowThroughRealDriverAndSerialTransportToTheSimulatedMaestro) {
  Bench b;
  ASSERT_EQ(b.link.start(), Status::ok);
  std::vector<double> pose = b.rig.rest_frame();
  std::unique_ptr<bool[]> known(new bool[2]());
  ASSERT_EQ(b.link.read_positions(pose, std::span<bool>(known.get(), 2)), Status::ok);
  EXPECT_FALSE(known[0]);  // no pulses yet: the Maestro cannot say where the servo is

  Controller controller(b.rig, b.show, {&b.link}, {.tick_period_s = 0.02});
  controller.begin(0.0, pose);
  StepDevice step(b);
  const std::atomic<int> no_interrupts{0};
  const RunResult run = run_loop(controller, {50, ClockMode::stepped, {}}, step, no_interrupts);
  EXPECT_EQ(controller.phase(), Phase::disabled);
  EXPECT_EQ(controller.latched_fault().cause, FaultCause::none);

  b.host.with_device([&](sim::ByteDevice&) {
    const auto& log = b.device.log();
    // Start: read and clear errors, speed and acceleration for each actuator, then one
    // Get Position per actuator.
    ASSERT_GE(log.size(), 7u + run.ticks);
    EXPECT_EQ(log[0].command, maestro::kGetErrors);
    EXPECT_EQ(log[1].command, maestro::kSetSpeed);
    EXPECT_EQ(log[1].channel, 2);
    EXPECT_EQ(log[1].values, std::vector<std::uint16_t>{0});
    EXPECT_EQ(log[3].command, maestro::kSetSpeed);
    EXPECT_EQ(log[3].channel, 3);
    EXPECT_EQ(log[3].values, std::vector<std::uint16_t>{20});  // 500 µs/s = 20 units
    EXPECT_EQ(log[5].command, maestro::kGetPosition);
    EXPECT_EQ(log[6].command, maestro::kGetPosition);
    // Then exactly one Set Multiple Targets (channels 2 and 3 together) per tick.
    std::size_t frames = 0;
    for (std::size_t i = 7; i < log.size(); ++i) {
      ASSERT_EQ(log[i].command, maestro::kSetMultipleTargets);
      ASSERT_EQ(log[i].channel, 2);
      ASSERT_EQ(log[i].values.size(), 2u);
      for (std::uint16_t q : log[i].values) {
        ASSERT_GE(q, 4000);
        ASSERT_LE(q, 8000);
      }
      ++frames;
    }
    EXPECT_EQ(frames, run.ticks);
    // The last frame is the rest pose: jaw 0 deg -> 1000 µs, pan 0 deg -> 1500 µs.
    EXPECT_EQ(log.back().values, (std::vector<std::uint16_t>{4000, 6000}));
    // The show's peak (25 deg jaw at 0.5 s -> 1833.3 µs) was commanded, up to the smoothing.
    std::uint16_t peak = 0;
    for (std::size_t i = 7; i < log.size(); ++i) peak = std::max(peak, log[i].values[0]);
    EXPECT_LE(peak, 7333);  // the corner is rounded by the acceleration and jerk limits
    EXPECT_GT(peak, 6900);
    EXPECT_EQ(b.device.errors(), 0);
  });
  // Let the servos settle, then check where they are: at rest.
  for (int i = 0; i < 100; ++i) b.host.with_device([&](sim::ByteDevice& d) { d.advance(0.01); });
  b.host.with_device([&](sim::ByteDevice&) {
    EXPECT_NEAR(b.device.servo_position_us(2), 1000, 2.5);
    EXPECT_NEAR(b.device.servo_position_us(3), 1500, 2.5);
  });
}

}  // namespace
}  // namespace avar::control

namespace avar::control {
namespace {

/// Two DYNAMIXEL joints; the second servo runs hot. The show keeps them working.
struct HotBus {
  Rig rig;
  playback::Show show;
  sim::SimDynamixel device;
  sim::SimWire wire;
  firmware_iface::DynamixelLink link;

  static Rig make_rig() {
    Rig r;
    r.name = "hot";
    for (const char* name : {"shoulder", "elbow"})
      r.channels.push_back({.name = name, .unit = "deg", .min = -90, .max = 90, .rest = 0, .max_velocity = 400,
                            .max_acceleration = 8000, .max_jerk = 400000, .ramp_velocity = 90, .where = {}});
    r.links.emplace_back().name = "bus";
    for (std::size_t c = 0; c < 2; ++c) {
      ActuatorSpec a;
      a.channel = rig::ChannelIndex{c};
      a.device_channel = static_cast<int>(c + 1);
      a.failsafe = c == 0 ? Failsafe::rest : Failsafe::release;
      r.actuators.push_back(a);
    }
    return r;
  }
  static playback::Show make_show() {
    playback::Show s;
    s.name = "swing";
    s.duration = 20;
    for (const char* channel : {"shoulder", "elbow"}) {
      playback::RawCurve raw;
      for (int i = 0; i <= 40; ++i) {
        playback::RawKey k;
        k.time = i * 0.5;
        k.value = i % 2 ? 80.0 : -80.0;
        raw.keys.push_back(k);
      }
      s.tracks.push_back({channel, raw, playback::Curve::build(raw), {}});
    }
    return s;
  }
  static sim::SimDynamixelConfig bus() {
    sim::SimDynamixelConfig c;
    c.servos.resize(2);
    c.servos[1].id = 2;
    c.servos[1].ambient_c = 70;
    c.servos[1].heating_c_per_s_at_full_load = 40;
    return c;
  }
  static firmware_iface::DynamixelLinkConfig link_config() {
    firmware_iface::DynamixelLinkConfig c;
    for (std::uint8_t id : {std::uint8_t{1}, std::uint8_t{2}}) {
      firmware_iface::DynamixelActuator a;
      a.channel = id - 1u;
      a.id = id;
      a.calibration = {-90, 90, 1024, 3072, false, 0};
      c.actuators.push_back(a);
    }
    return c;
  }
  HotBus() : rig(make_rig()), show(make_show()), device(bus()), wire(device, 1'000'000), link(wire, link_config()) {}
};

TEST(EndToEnd, AServoThatOverheatsMidShowFaultsItsChannelAndTheFigureGoesToItsFailsafe) {
  HotBus b;
  ASSERT_EQ(b.link.start(), Status::ok);
  constexpr double kDt = 0.01;
  Controller c(b.rig, b.show, {&b.link}, {.tick_period_s = kDt});
  c.begin(0, std::vector<double>{0, 0});
  std::vector<firmware_iface::ChannelTelemetry> telemetry(2);
  int k = 0;
  for (; k < 3000 && c.phase() != Phase::faulted; ++k) {
    c.tick(k * kDt);
    b.device.advance(kDt);
    b.link.read_telemetry(telemetry);
    c.feed_telemetry(telemetry);
  }
  ASSERT_EQ(c.phase(), Phase::faulted) << "the hot servo never overheated";
  EXPECT_EQ(c.latched_fault().cause, FaultCause::device_overheat);
  EXPECT_EQ(c.latched_fault().index, 1u);
  EXPECT_GE(c.latched_fault().value, 80);  // the temperature it reported (°C)
  EXPECT_GT(c.latched_fault().time_s, 1.0);  // it was running, not failing from the start
  for (; c.active() && k < 6000; ++k) {
    c.tick(k * kDt);
    b.device.advance(kDt);
  }
  EXPECT_FALSE(c.active());
  // Shoulder: eased to rest; elbow: released (torque off on the device).
  EXPECT_NEAR(c.commanded()[0], 0, 1e-9);
  EXPECT_NEAR(b.device.position(0), 2048, 5);
  EXPECT_EQ(b.device.read_u8(1, firmware_iface::dynamixel::kTorqueEnable), 0);
}

}  // namespace
}  // namespace avar::control
