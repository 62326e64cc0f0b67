// Look-at gaze on the example rig with two eyes (examples/rigs/gaze-eyes.yaml): read against the
// rig's kinematics, then run through control::IdleLayer and checked with forward kinematics of
// the frames it produced: the sight lines meet at a near target and are nearly parallel for a
// far one, the eyes stay on the target while the head follows, the head waits its delay, every
// channel stays within its range and velocity limit, and the tick allocates nothing.

#include <gtest/gtest.h>

#include "../support/allocation_counter.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <vector>

#include "../support/input_errors.hpp"
#include "avar/config/idle_section.hpp"
#include "avar/config/rig_file.hpp"
#include "avar/control/idle_layer.hpp"
#include "avar/kinematics/forward_kinematics.hpp"

namespace avar::config {
namespace {

const std::string kLookAtRig = std::string(AVAR_SOURCE_DIR) + "/examples/rigs/gaze-eyes.yaml";

std::string look_at_rig_text(const std::string& file = kLookAtRig) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string look_at_error(const std::string& text) { return testing::load_error(load_rig_file, text, "look_at_rig.yaml"); }

/// A figure loaded with its idle section, and forward kinematics of frames of it.
struct LookAtFigure {
  rig::Rig rig;
  playback::IdleSpec spec;
  explicit LookAtFigure(const std::string& path) : rig(load_rig_file(path)), spec(*load_idle_section(rig, path)) {}

  std::vector<double> rest() const {
    std::vector<double> frame;
    for (const rig::ChannelSpec& c : rig.channels) frame.push_back(c.rest);
    return frame;
  }
  /// Each eye's sight line (origin, unit direction) in the world for a frame.
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> sight_lines(const std::vector<double>& frame) const {
    const rig::RigKinematics& kin = *rig.kinematics;
    std::vector<double> q(kin.model.dof(), 0.0);
    for (const rig::JointBinding& b : kin.bindings) q[b.q_index] = b.to_joint(frame[b.channel]);
    kinematics::Workspace ws(kin.model);
    EXPECT_EQ(kinematics::forward_kinematics(kin.model, q, ws), Status::ok);
    const playback::GazeLookAt& look = *spec.gaze->look_at;
    const Eigen::Vector3d axis(look.aim_axis[0], look.aim_axis[1], look.aim_axis[2]);
    std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> lines;
    for (const std::size_t e : look.effectors) {
      const Eigen::Isometry3d pose = kinematics::effector_pose(kin.model, ws, e);
      lines.emplace_back(pose.translation(), (pose.linear() * axis).normalized());
    }
    return lines;
  }
};

/// Distance from a point to the ray from `origin` along unit `direction`.
double look_at_miss(const std::pair<Eigen::Vector3d, Eigen::Vector3d>& line, const Eigen::Vector3d& point) {
  const Eigen::Vector3d to = point - line.first;
  return (to - to.dot(line.second) * line.second).norm();
}

/// Closest approach of two lines: the midpoint of the shortest segment between them.
Eigen::Vector3d look_at_meeting(const std::pair<Eigen::Vector3d, Eigen::Vector3d>& a,
                                const std::pair<Eigen::Vector3d, Eigen::Vector3d>& b) {
  const Eigen::Vector3d w = a.first - b.first;
  const double d = a.second.dot(b.second), e = a.second.dot(w), f = b.second.dot(w);
  const double denom = 1 - d * d;
  const double s = (d * f - e) / denom, t = (f - d * e) / denom;
  return 0.5 * ((a.first + s * a.second) + (b.first + t * b.second));
}

TEST(IdleLookAt, TheExampleRigReadsItsEyesFromTheKinematics) {
  const LookAtFigure fig(kLookAtRig);
  ASSERT_TRUE(fig.spec.gaze && fig.spec.gaze->look_at);
  const playback::GazeLookAt& look = *fig.spec.gaze->look_at;
  const kinematics::Model& model = fig.rig.kinematics->model;
  ASSERT_EQ(look.effectors.size(), 2u);
  EXPECT_EQ(look.effectors[0], model.find_effector("left_eye"));
  EXPECT_EQ(look.effectors[1], model.find_effector("right_eye"));
  EXPECT_EQ(look.mount_joint, model.find_joint("tilt"));  // the neck's tilt carries the eyes
  std::vector<std::size_t> eye_channels = look.eye_channels;
  std::sort(eye_channels.begin(), eye_channels.end());
  EXPECT_EQ(eye_channels, (std::vector<std::size_t>{*fig.rig.find_channel("eyes_tilt"), *fig.rig.find_channel("eye_l_pan"),
                                                    *fig.rig.find_channel("eye_r_pan")}));
  // Between the pupils, 0.012 m ahead of the eye joints: x 0.08 + 0.012, z 0.30 + 0.06 + 0.04.
  EXPECT_NEAR(look.centre[0], 0.092, 1e-12);
  EXPECT_NEAR(look.centre[1], 0, 1e-12);
  EXPECT_NEAR(look.centre[2], 0.40, 1e-12);
  EXPECT_NEAR(look.ahead[0], 1, 1e-12);
  EXPECT_NEAR(look.left[1], 1, 1e-12);
  EXPECT_NEAR(look.half_interocular_m, 0.032, 1e-12);
  EXPECT_DOUBLE_EQ(look.far_m, 2.0);
  EXPECT_DOUBLE_EQ(look.near_m, 0.3);
  EXPECT_DOUBLE_EQ(fig.spec.gaze->near_probability, 0.25);
  // Positive neck pan turns the head left and positive neck tilt up: one channel degree each.
  EXPECT_NEAR(look.head_units_per_degree[0], 1, 1e-12);
  EXPECT_NEAR(look.head_units_per_degree[1], 1, 1e-12);
  // The eyes' limits in degrees of gaze: the tightest (eyes_tilt, 400 deg/s) over the parallax
  // gain near / (near - reach), reach the farthest eye joint from the centre.
  const double reach = std::hypot(0.012, 0.032);
  EXPECT_NEAR(look.eye_limits.max_velocity, 400 * (0.3 - reach) / 0.3, 1e-9);
  // The old per-eye channels are not used.
  EXPECT_FALSE(fig.spec.gaze->eyes_pan || fig.spec.gaze->left_pan || fig.spec.gaze->eyes_tilt);
}

TEST(IdleLookAt, MistakesAreNamedWhereTheyStand) {
  const std::string rig = look_at_rig_text();
  const std::string unknown =
      look_at_error(testing::replace(rig, "effectors: [left_eye, right_eye]", "effectors: [left_eye, rigth_eye]"));
  EXPECT_NE(unknown.find("expected an effector of the rig's kinematics, found 'rigth_eye'"), std::string::npos) << unknown;
  EXPECT_EQ(unknown.rfind(':', 0), 0u);  // file:line:col first
  const std::string units =
      look_at_error(testing::replace(testing::replace(rig, "eye_l_pan:      {unit: deg", "eye_l_pan:      {unit: step"),
                                     "channel: eye_l_pan}", "channel: eye_l_pan, scale: 0.01}"));
  EXPECT_NE(units.find("needs the eye channels in deg or rad"), std::string::npos) << units;
  const std::string both = look_at_error(testing::replace(rig, "    look_at:", "    eyes: {pan: eye_l_pan}\n    look_at:"));
  EXPECT_NE(both.find("either eyes (channels) or look_at (effectors)"), std::string::npos) << both;
  const std::string near =
      look_at_error(testing::replace(rig, "distance: {far: 2.0, near: 0.3", "distance: {far: 2.0, near: 0.05"));
  EXPECT_NE(near.find("expected the near distance at least"), std::string::npos) << near;
  const std::string order =
      look_at_error(testing::replace(rig, "distance: {far: 2.0, near: 0.3", "distance: {far: 0.2, near: 0.3"));
  EXPECT_NE(order.find("near distance at most the far one"), std::string::npos) << order;
  const std::string shared =
      look_at_error(testing::replace(rig, "lids: {lid_left: {open: 80, closed: 0}", "lids: {eye_l_pan: {open: 0, closed: 10}"));
  EXPECT_NE(shared.find("already driven by idle blinks"), std::string::npos) << shared;
  const std::string headless = look_at_error(testing::replace(rig, "effectors: [left_eye, right_eye]", "effectors: [eyes]"));
  EXPECT_NE(headless.find("has no joint of its own below the head's"), std::string::npos) << headless;
  // A head channel that drives no joint cannot turn the head through the kinematics.
  std::string unbound = testing::replace(
      rig, "  lid_left:       {unit:", "  brow:           {unit: deg, min: -10, max: 10, rest: 0}\n  lid_left:       {unit:");
  unbound = testing::replace(unbound, "  - {channel: lid_left, ",
                             "  - {channel: brow,          link: head, device_channel: 7, calibration: {min_us: 1000, max_us: "
                             "2000}}\n  - {channel: lid_left, ");
  unbound = testing::replace(unbound, "tilt: neck_tilt, follow", "tilt: brow, follow");
  const std::string head = look_at_error(unbound);
  EXPECT_NE(head.find("channel 'brow' drives no joint of it"), std::string::npos) << head;
  // Without kinematics (hello-head): look-at gaze cannot aim.
  const std::string hello = look_at_rig_text(std::string(AVAR_SOURCE_DIR) + "/examples/rigs/hello-head.yaml");
  const std::string no_kin =
      look_at_error(testing::replace(hello, "eyes: {pan: eyes_pan, tilt: eyes_tilt}", "look_at: {effectors: [eyes]}"));
  EXPECT_NE(no_kin.find("expected a kinematics section in the rig"), std::string::npos) << no_kin;
  const std::string distance = look_at_error(testing::replace(hello, "fixation_s: [0.4, 2.5]", "distance: {far: 2}"));
  EXPECT_NE(distance.find("distance is for look-at gaze"), std::string::npos) << distance;
}

/// A seeded idle run of the look-at rig through the IdleLayer at `rate` Hz, calling `tick` with
/// the time, the layer and the frame it produced after each apply (from 1 s, when idle has
/// faded in).
template <class Tick>
void look_at_run(const LookAtFigure& fig, std::uint64_t seed, double seconds, double rate, Tick&& tick) {
  control::IdleLayer idle(fig.spec, seed, std::vector<char>(fig.rig.channels.size(), 0), &*fig.rig.kinematics);
  const std::vector<double> rest = fig.rest();
  std::vector<double> frame = rest;
  const auto ticks = static_cast<long>(seconds * rate);
  for (long k = 0; k <= ticks; ++k) {
    const double t = static_cast<double>(k) / rate;
    std::copy(rest.begin(), rest.end(), frame.begin());
    idle.apply(t, frame);
    if (t >= 1.0) tick(t, idle, frame);
  }
}

TEST(IdleLookAt, SightLinesMeetAtANearTargetAndRunNearlyParallelForAFarOne) {
  const LookAtFigure fig(kLookAtRig);
  const double h = fig.spec.gaze->look_at->half_interocular_m;
  std::size_t near_checked = 0, far_checked = 0, moving_head = 0;
  double worst_near = 0, worst_miss = 0, worst_miss_moving = 0, previous_head = 0, smallest_near = 1, largest_far = 0;
  std::uint64_t converged = 0;
  for (std::uint64_t seed : {3u, 11u}) {
    look_at_run(fig, seed, 40, 100, [&](double t, const control::IdleLayer& idle, const std::vector<double>& frame) {
      const playback::GazeGenerator& gaze = *idle.generator().gaze();
      const control::IkStats& stats = idle.look_at()->stats();
      const bool solved = stats.converged > converged;  // this tick's solve converged
      converged = stats.converged;
      const double head = frame[*fig.rig.find_channel("neck_pan")];
      const bool head_moves = std::abs(head - previous_head) > 0.02;
      previous_head = head;
      // Fixating (the saccade over), the eyes within reach of the target.
      if (!solved || t < gaze.saccade_start() + gaze.last_saccade_s()) return;
      const playback::GazePoint point = gaze.gaze_point();
      const Eigen::Vector3d target = idle.look_at()->world_point(point);
      const auto lines = fig.sight_lines(frame);
      for (const auto& line : lines) {
        worst_miss = std::max(worst_miss, look_at_miss(line, target));
        if (head_moves) worst_miss_moving = std::max(worst_miss_moving, look_at_miss(line, target));
      }
      if (head_moves) ++moving_head;
      // The angle between the sight lines: 2 atan(h / d) straight ahead, less off to a side
      // (where the eyes' baseline is foreshortened).
      const double angle = std::acos(std::clamp(lines[0].second.dot(lines[1].second), -1.0, 1.0));
      const double ahead = 2 * std::atan(h / point.distance_m);
      EXPECT_LE(angle, ahead + 1e-4);
      EXPECT_GT(angle, 0.75 * ahead);
      if (point.distance_m < 0.5) {
        // Vergence from the geometry: the lines meet at the target.
        worst_near = std::max(worst_near, (look_at_meeting(lines[0], lines[1]) - target).norm());
        smallest_near = std::min(smallest_near, angle);
        ++near_checked;
      } else {
        largest_far = std::max(largest_far, angle);  // 2 atan(0.032 / 2) = 1.83° at most
        ++far_checked;
      }
    });
    converged = 0;
  }
  EXPECT_GT(near_checked, 200u);
  EXPECT_GT(far_checked, 1000u);
  EXPECT_LT(worst_near, 1e-3);                            // m
  EXPECT_LT(largest_far * 180 / std::numbers::pi, 1.84);  // far: nearly parallel
  EXPECT_GT(smallest_near, 4 * largest_far);              // near: converging (12.2° straight ahead)
  // The eyes stay on the target while the head follows (they counter-turn): checked on ticks
  // where the head moved.
  EXPECT_LT(worst_miss, 1e-3);         // m
  EXPECT_LT(worst_miss_moving, 1e-3);  // m, on ticks where the head turned by more than 0.02°
  EXPECT_GT(moving_head, 200u);
}

TEST(IdleLookAt, NoChannelLeavesItsRangeOrOutrunsItsVelocityOverALongSeededRun) {
  const LookAtFigure fig(kLookAtRig);
  const double rate = 100;
  const std::vector<std::size_t> eyes = fig.spec.gaze->look_at->eye_channels;
  std::vector<double> peak(fig.rig.channels.size(), 0.0);
  std::uint64_t saccades = 0;
  for (std::uint64_t seed : {1u, 2u, 5u}) {
    std::vector<double> previous;
    look_at_run(fig, seed, 120, rate, [&](double, const control::IdleLayer& idle, const std::vector<double>& frame) {
      for (std::size_t c = 0; c < frame.size(); ++c) {
        const rig::ChannelSpec& ch = fig.rig.channels[c];
        ASSERT_GE(frame[c], ch.min + ch.soft_margin - 1e-9) << ch.name;
        ASSERT_LE(frame[c], ch.max - ch.soft_margin + 1e-9) << ch.name;
        if (!previous.empty()) peak[c] = std::max(peak[c], std::abs(frame[c] - previous[c]) * rate);
      }
      previous = frame;
      saccades = idle.generator().gaze()->saccades();
    });
    EXPECT_GT(saccades, 50u);
  }
  for (std::size_t c = 0; c < peak.size(); ++c) {
    const rig::ChannelSpec& ch = fig.rig.channels[c];
    EXPECT_LE(peak[c], ch.max_velocity) << ch.name;
  }
  // The saccades' peaks stay within the share the eyes give them (and the head's counter-turn),
  // and they are real saccades, well above the head's pace.
  for (const std::size_t c : eyes) {
    EXPECT_LE(peak[c], (playback::kGazeSaccadeShare + playback::kGazeHeadShare) * fig.rig.channels[c].max_velocity)
        << fig.rig.channels[c].name;
    EXPECT_GT(peak[c], 150) << fig.rig.channels[c].name;
  }
}

TEST(IdleLookAt, TheHeadFollowsAfterItsDelay) {
  // Long fixations, so the head has settled before each saccade.
  const std::string path = testing::write_temp_file(
      "look_at_delay.yaml",
      testing::replace(testing::replace(look_at_rig_text(), "fixation_s: [0.4, 2.5]", "fixation_s: [3, 3.5]"),
                       "breathing: {period_s: 4.5, jitter: 0.1, channels: {neck_tilt: 1.5}}", ""));
  const LookAtFigure fig(path);
  const double delay = fig.spec.gaze->head_delay_s;  // 0.15 s
  ASSERT_DOUBLE_EQ(delay, 0.15);
  const std::size_t pan = *fig.rig.find_channel("neck_pan");
  const double rate = 200;
  std::vector<double> times, heads, starts;
  std::uint64_t seen = 0;
  look_at_run(fig, 9, 40, rate, [&](double t, const control::IdleLayer& idle, const std::vector<double>& frame) {
    times.push_back(t);
    heads.push_back(frame[pan]);
    const playback::GazeGenerator& gaze = *idle.generator().gaze();
    if (gaze.saccades() > seen) {
      seen = gaze.saccades();
      starts.push_back(gaze.saccade_start());
    }
  });
  const auto head_at = [&](double t) {
    const auto k = static_cast<std::size_t>(std::lround((t - times.front()) * rate));
    return heads.at(std::min(k, heads.size() - 1));
  };
  std::size_t checked = 0;
  for (const double t0 : starts) {
    if (t0 + 1 > times.back() || t0 < 2) continue;
    const double before = head_at(t0), waited = head_at(t0 + delay - 0.01), after = head_at(t0 + delay + 0.2);
    // Still during the delay (settled from the last fixation), moving once it is over.
    EXPECT_NEAR(waited, before, 0.05) << "saccade at " << t0;
    if (std::abs(head_at(t0 + 2.5) - before) > 2) {
      EXPECT_GT(std::abs(after - waited), 0.3) << "saccade at " << t0;
      ++checked;
    }
  }
  EXPECT_GE(checked, 5u);
}

TEST(IdleLookAt, TheTickAllocatesNothing) {
  const LookAtFigure fig(kLookAtRig);
  control::IdleLayer idle(fig.spec, 4, std::vector<char>(fig.rig.channels.size(), 0), &*fig.rig.kinematics);
  std::vector<double> frame = fig.rest();
  idle.apply(0, frame);  // the first (cold) solve
  const long before = testing::allocations.load();
  for (int k = 1; k < 3000; ++k) idle.apply(k * 0.01, frame);
  EXPECT_EQ(testing::allocations.load() - before, 0);
  EXPECT_GT(idle.generator().gaze()->saccades(), 5u);
  EXPECT_EQ(idle.look_at()->stats().failed, 0u);
}

TEST(IdleLookAt, LookAtGazeNeedsTheKinematicsToRun) {
  const LookAtFigure fig(kLookAtRig);
  EXPECT_THROW(control::IdleLayer(fig.spec, 1, std::vector<char>(fig.rig.channels.size(), 0)), std::invalid_argument);
}

}  // namespace
}  // namespace avar::config
