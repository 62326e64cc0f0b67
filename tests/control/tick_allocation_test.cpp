// The real-time rule: once built, the tick allocates nothing. Counts every operator new in this
// test binary and asserts none happens across thousands of ticks through every phase, with the
// real Maestro link encoding into a transport.
#include <gtest/gtest.h>

#include "../support/allocation_counter.hpp"
#include "../support/discard_transport.hpp"

#include "avar/control/controller.hpp"
#include "avar/control/live_inputs.hpp"
#include "avar/control/threaded_link.hpp"
#include "avar/firmware_iface/maestro_link.hpp"
#include "avar/kinematics/model_builder.hpp"

#include <atomic>
#include <memory>
#include "../support/rig_names.hpp"

namespace avar::control {
namespace {

struct Scene {
  Rig rig;
  playback::Show show;
  firmware_iface::MaestroLinkConfig link_config;
};

Scene scene() {
  Scene sc;
  Rig& rig = sc.rig;
  playback::Show& show = sc.show;
  firmware_iface::MaestroLinkConfig& link_config = sc.link_config;
  rig.name = "alloc";
  link_config.channel_count = 12;
  for (int i = 0; i < 8; ++i) {
    const std::string name = "ch" + std::to_string(i);
    rig.channels.push_back({.name = name, .unit = "deg", .min = -45, .max = 45, .rest = 0, .max_velocity = 400, .max_acceleration = 4000, .max_jerk = 40000, .ramp_velocity = 60, .tracking_tolerance = 0.5, .where = {}});
    // Two runs of consecutive device channels (0-3 and 6-9) exercise both packet kinds.
    const int device_channel = i < 4 ? i : i + 2;
    link_config.actuators.push_back({static_cast<std::size_t>(i), device_channel, {-45, 45, 1000, 2000, i % 2 == 1, 5}, {}, {}});
    ActuatorSpec spec;
    spec.channel = rig::ChannelIndex{static_cast<std::size_t>(i)};
    spec.failsafe = i % 3 == 0 ? Failsafe::release : (i % 3 == 1 ? Failsafe::hold : Failsafe::rest);
    rig.actuators.push_back(spec);
  }
  rig.links.emplace_back().name = "bus";
  show.name = "alloc";
  show.duration = 4;
  for (int i = 0; i < 8; ++i) {
    playback::RawCurve raw;
    for (int k = 0; k <= 40; ++k) {
      playback::RawKey key;
      key.time = k * 0.1;
      key.value = (k % 2 ? 40.0 : -40.0) * (i + 1) / 8.0;
      key.interpolation = static_cast<playback::Interpolation>(k % 3);
      key.left = playback::Handle{key.time - 0.03, key.value};
      key.right = playback::Handle{key.time + 0.03, key.value};
      raw.keys.push_back(key);
    }
    playback::Curve curve = playback::Curve::build(raw);
    show.tracks.push_back({"ch" + std::to_string(i), raw, std::move(curve), {}});
  }
  return sc;
}

/// The scene with channels 0 and 1 as the pan and tilt of a head whose eye follows a moving
/// target through inverse kinematics (their tracks removed).
Scene scene_with_targets() {
  Scene sc = scene();
  kinematics::ModelBuilder b;
  b.add_joint({"pan", kinematics::JointType::revolute, "", Eigen::Isometry3d::Identity(), Eigen::Vector3d::UnitZ(), -0.78, 0.78});
  b.add_joint({"tilt", kinematics::JointType::revolute, "pan", Eigen::Isometry3d::Identity(), Eigen::Vector3d::UnitY(), -0.78, 0.78});
  b.add_effector({"eye", "tilt", Eigen::Isometry3d::Identity()});
  const double deg = 3.141592653589793 / 180;
  sc.rig.kinematics = RigKinematics{b.build(), {{0, 0, deg, 0}, {1, 1, deg, 0}}, {}, {}};
  sc.show.tracks.erase(sc.show.tracks.begin(), sc.show.tracks.begin() + 2);
  playback::TargetTrack target;
  target.effector = "eye";
  target.kind = playback::TargetKind::aim;
  const double ends[3][2] = {{1, 1}, {-0.5, 0.5}, {-0.3, 0.4}};
  for (std::size_t a = 0; a < 3; ++a) {
    playback::RawKey k0, k1;
    k0.value = ends[a][0];
    k1.time = 4;
    k1.value = ends[a][1];
    k0.interpolation = playback::Interpolation::sine;
    target.raw[a].keys = {k0, k1};
    target.xyz[a] = playback::Curve::build(target.raw[a]);
  }
  sc.show.targets.push_back(std::move(target));
  return sc;
}

/// The target scene with the eye aiming along a path at an eased speed instead of x, y, z curves.
Scene scene_with_path_target() {
  Scene sc = scene_with_targets();
  playback::TargetTrack& target = sc.show.targets.front();
  playback::PathSpec path;
  path.points = {{1, -0.5, -0.3}, {1, 0, 0.4}, {1, 0.5, -0.3}, {1, 0.2, 0.2}};
  path.spline = playback::PathSpline::catmull_rom;
  path.from = 0.5;
  path.to = 3.5;
  path.speed = playback::DistanceTime(playback::DistanceTimeShape::sine_constant_middle, 0.2, 0.8);
  target.path.emplace(path);
  return sc;
}

void expect_no_allocation_in_ticks_with_ik(const Scene& sc) {
  testing::DiscardTransport transport;
  firmware_iface::MaestroLink link(transport, sc.link_config);
  Controller controller(sc.rig, sc.show, {&link}, {.tick_period_s = 0.001});
  controller.begin(0.0, sc.rig.rest_frame());
  std::vector<firmware_iface::ChannelTelemetry> telemetry(sc.rig.channels.size());

  const long before = testing::allocations.load();
  int k = 0;
  for (; controller.active() && k < 100000; ++k) {
    controller.tick(k * 0.001);
    for (std::size_t c = 0; c < telemetry.size(); ++c) {
      telemetry[c].position = controller.commanded()[c];
      telemetry[c].temperature_c = 40;
      ++telemetry[c].updates;
    }
    controller.feed_telemetry(telemetry);
  }
  const long after = testing::allocations.load();
  EXPECT_GT(k, 3000);
  ASSERT_NE(controller.ik(), nullptr);
  EXPECT_GT(controller.ik()->stats().converged, 3000u);
  EXPECT_EQ(after - before, 0) << "allocations during " << k << " ticks";
}

TEST(TickAllocation, NoAllocationWithInverseKinematicsAndDeviceTelemetry) { expect_no_allocation_in_ticks_with_ik(scene_with_targets()); }

TEST(TickAllocation, NoAllocationWithAPathTarget) { expect_no_allocation_in_ticks_with_ik(scene_with_path_target()); }

TEST(TickAllocation, NoAllocationInAnyPhaseOfTheTick) {
  const Scene sc = scene();
  testing::DiscardTransport transport;
  firmware_iface::MaestroLink link(transport, sc.link_config);
  Controller controller(sc.rig, sc.show, {&link}, {.tick_period_s = 0.001});
  controller.begin(0.0, sc.rig.rest_frame());

  const long before = testing::allocations.load();
  int k = 0;
  bool stopped = false;
  for (; controller.active() && k < 100000; ++k) {
    if (!stopped && controller.show_time() > 3.0) {
      controller.request_stop(k * 0.001);
      stopped = true;
    }
    controller.tick(k * 0.001);
  }
  const long after = testing::allocations.load();
  EXPECT_TRUE(stopped);
  EXPECT_GT(k, 3000);
  EXPECT_GT(transport.bytes_written(), 0u);
  EXPECT_EQ(after - before, 0) << "allocations during " << k << " ticks";
}

// Live inputs mixed every tick: controls moving (posted between ticks, as input threads do),
// relative and held mappings, a direct channel, crossfades and timeouts; nothing allocates.
TEST(TickAllocation, NoAllocationWithLiveInputsMixedOverTheShow) {
  const Scene sc = scene();
  testing::DiscardTransport transport;
  firmware_iface::MaestroLink link(transport, sc.link_config);
  std::vector<LiveChannel> channels;
  for (const rig::ChannelSpec& c : sc.rig.channels) channels.push_back({c.name, c.min, c.max});
  ControlMapping absolute, relative;
  absolute.control = "x";
  absolute.low = -45;
  absolute.high = 45;
  absolute.timeout_s = 0.2;
  relative.control = "y";
  relative.channel = 1;
  relative.mode = MappingMode::relative;
  relative.rate = 30;
  relative.hold = "b";
  relative.shape.smoothing_s = 0.05;
  LiveInputs live(channels, {absolute, relative});
  Controller controller(sc.rig, sc.show, {&link}, {.tick_period_s = 0.001, .live = &live});
  controller.begin(0.0, sc.rig.rest_frame());
  live.sink().post("b", 1, false, 0);  // the map's first insertions happen here, before counting

  const long before = testing::allocations.load();
  int k = 0;
  for (; controller.active() && k < 6000; ++k) {
    if (k % 7 == 0) live.sink().post("x", std::sin(k * 0.01), true, k);
    if (k % 11 == 0) live.sink().post("y", 0.5, true, k);
    if (k == 2000) live.sink().post("channel/ch2", 30, false, k);
    controller.tick(k * 0.001);
  }
  const long after = testing::allocations.load();
  EXPECT_EQ(after - before, 0) << "allocations during " << k << " ticks";
  EXPECT_TRUE(live.touched()[0]);
  EXPECT_TRUE(live.touched()[2]);
}

// The same through the I/O thread and its mailbox, with feedback, a tracking fault and every
// fail-safe action: nothing allocates on either thread.
TEST(TickAllocation, NoAllocationThroughTheIoThreadAndTheFaultPath) {
  const Scene sc = scene();
  testing::DiscardTransport transport;
  firmware_iface::MaestroLink link(transport, sc.link_config);
  ThreadedLink threaded(link, sc.rig.channels.size(), 100000);
  Controller controller(sc.rig, sc.show, {&threaded}, {.tick_period_s = 0.001});
  controller.begin(0.0, sc.rig.rest_frame());
  std::vector<double> measured(sc.rig.channels.size(), 0.0);
  std::unique_ptr<bool[]> known(new bool[sc.rig.channels.size()]());

  const long before = testing::allocations.load();
  int k = 0;
  for (; controller.active() && k < 100000; ++k) {
    std::copy(controller.commanded().begin(), controller.commanded().end(), measured.begin());
    known[0] = true;
    if (controller.show_time() > 2.0) measured[0] += 1.0;  // beyond the tracking tolerance
    controller.feed_back(measured, std::span<const bool>(known.get(), sc.rig.channels.size()));
    controller.tick(k * 0.001);
  }
  const long after = testing::allocations.load();
  EXPECT_EQ(controller.latched_fault().cause, FaultCause::tracking_error);
  EXPECT_GT(k, 2000);
  EXPECT_EQ(after - before, 0) << "allocations during " << k << " ticks";
}

}  // namespace
}  // namespace avar::control
