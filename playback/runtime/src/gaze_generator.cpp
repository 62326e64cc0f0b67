#include "avar/playback/runtime/gaze_generator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "avar/playback/runtime/min_jerk.hpp"

namespace avar::playback {
namespace {

constexpr double kGazeHeadStep = 0.005;  // s, the head filter's longest integration step

/// Look-at gaze: the vergence of a target `distance` m away, as its inverse distance (1/m): the
/// target's distance moves evenly in it, as each eye's inward turn atan(half interocular ×
/// 1/distance) nearly does.
double gaze_inverse_distance(double distance) noexcept { return 1.0 / distance; }

double gaze_channel_speed(const std::optional<std::size_t>& c, std::span<const IdleChannelLimits> limits) noexcept {
  return c ? limits[*c].max_velocity : std::numeric_limits<double>::infinity();
}

}  // namespace

double saccade_duration(double amplitude_deg) noexcept { return 0.021 + 0.0022 * std::abs(amplitude_deg); }

GazeGenerator::GazeGenerator(const GazeSpec& spec, std::span<const IdleChannelLimits> limits, std::uint64_t seed)
    : spec_(spec), limits_(limits.begin(), limits.end()), random_(seed) {
  // The head's counter-turn must leave the eyes their share: its speed is capped by the eyes'.
  std::array<double, 2> eye_speed{};
  if (spec_.look_at) {
    // Gaze units are degrees; the eyes' limits come in degrees of gaze, the head's are converted.
    eye_speed = {spec_.look_at->eye_limits.max_velocity, spec_.look_at->eye_limits.max_velocity};
    head_scale_ = spec_.look_at->head_units_per_degree;
    gaze_[2] = from_[2] = to_[2] = gaze_inverse_distance(spec_.look_at->far_m);
  } else {
    eye_speed = {std::min({gaze_channel_speed(spec_.eyes_pan, limits), gaze_channel_speed(spec_.left_pan, limits),
                           gaze_channel_speed(spec_.right_pan, limits)}),
                 gaze_channel_speed(spec_.eyes_tilt, limits)};
  }
  const std::array<std::optional<std::size_t>, 2> head{spec_.head_pan, spec_.head_tilt};
  for (std::size_t a = 0; a < 2; ++a) {
    if (!head[a]) continue;
    const double units = std::max(std::abs(head_scale_[a]), 1e-12);  // head channel units per gaze unit
    head_speed_cap_[a] = std::min(kGazeSaccadeShare * limits[*head[a]].max_velocity / units, kGazeHeadShare * eye_speed[a]);
    head_accel_cap_[a] = kGazeSaccadeShare * limits[*head[a]].max_acceleration / units;
  }
}

void GazeGenerator::aim_eyes(std::span<double> frame) noexcept {
  if (spec_.look_at && aim_) aim_->aim(gaze_point(), frame);
}

GazePoint GazeGenerator::gaze_point() const noexcept {
  return {gaze_[0], gaze_[1], gaze_[2] > 0 ? 1.0 / gaze_[2] : std::numeric_limits<double>::infinity()};
}

void GazeGenerator::begin_saccade(double t) noexcept {
  from_ = gaze_;
  to_[0] = random_.uniform(spec_.pan_min, spec_.pan_max);
  to_[1] = random_.uniform(spec_.tilt_min, spec_.tilt_max);
  const bool near = random_.chance(spec_.near_probability);
  if (spec_.look_at) to_[2] = gaze_inverse_distance(near ? spec_.look_at->near_m : spec_.look_at->far_m);
  else to_[2] = near ? spec_.vergence : 0.0;
  const double dpan = to_[0] - from_[0], dtilt = to_[1] - from_[1], dverg = to_[2] - from_[2];
  amplitude_ = std::hypot(dpan, dtilt);
  double d = saccade_duration(amplitude_);
  // Look-at: the target's direction and vergence move along the minimum-jerk profile and the eyes
  // are solved for it every sample (the head moves on through the fixations, so the eyes need a
  // solve per sample to counter-turn anyway, and the sight line sweeps straight to the target).
  // No eye joint turns faster than the direction's pan, tilt and vergence together (a pan-tilt
  // eye turns by at most that much of one of them per degree of gaze), times the parallax gain
  // of a near target, which eye_limits already takes off the joints' limits. Each eye's inward
  // turn atan(h/distance) changes by at most h × the change of 1/distance (radians).
  if (spec_.look_at) {
    const double dverg_deg = spec_.look_at->half_interocular_m * std::abs(dverg) * 180 / std::numbers::pi;
    d = min_jerk_duration(std::abs(dpan) + std::abs(dtilt) + dverg_deg, spec_.look_at->eye_limits, kGazeSaccadeShare, d);
  }
  // Each eye channel moves its own component (a per-eye pan also its vergence).
  if (spec_.eyes_pan) d = min_jerk_duration(dpan, limits_[*spec_.eyes_pan], kGazeSaccadeShare, d);
  if (spec_.left_pan) d = min_jerk_duration(std::abs(dpan) + std::abs(dverg), limits_[*spec_.left_pan], kGazeSaccadeShare, d);
  if (spec_.right_pan) d = min_jerk_duration(std::abs(dpan) + std::abs(dverg), limits_[*spec_.right_pan], kGazeSaccadeShare, d);
  if (spec_.eyes_tilt) d = min_jerk_duration(dtilt, limits_[*spec_.eyes_tilt], kGazeSaccadeShare, d);
  saccade_start_ = t;
  saccade_s_ = d;
  next_saccade_ = t + d + random_.uniform(spec_.fixation_min, spec_.fixation_max);
  ++saccades_;
  // The head's new goal, due after the delay; the oldest pending goal gives way when full.
  if (pending_count_ == pending_.size()) {
    std::copy(pending_.begin() + 1, pending_.end(), pending_.begin());
    --pending_count_;
  }
  pending_[pending_count_++] = {t + spec_.head_delay_s, spec_.head_follow * to_[0], spec_.head_follow * to_[1]};
}

void GazeGenerator::follow_head(double t) noexcept {
  const double omega = 1.0 / std::max(spec_.head_smoothing_s, 1e-3);
  while (head_t_ < t) {
    const double h = std::min(kGazeHeadStep, t - head_t_);
    // A goal steers the steps that start when it is due or later: a step (or the part of one
    // before a sample) never feels a goal due after it began, so the head's path does not
    // depend on where the samples fall.
    while (pending_count_ > 0 && pending_[0].due <= head_t_) {
      head_goal_ = {pending_[0].pan, pending_[0].tilt};
      std::copy(pending_.begin() + 1, pending_.end(), pending_.begin());
      --pending_count_;
    }
    head_t_ += h;
    for (std::size_t a = 0; a < 2; ++a) {
      // Critically damped: x'' = ω²(goal − x) − 2ω x', within the head's caps.
      const double accel = std::clamp(omega * omega * (head_goal_[a] - head_[a]) - 2 * omega * head_velocity_[a],
                                      -head_accel_cap_[a], head_accel_cap_[a]);
      // The mean of the step's velocities: exact for its constant acceleration, so that a step
      // shorter than kGazeHeadStep (a sample between steps) asks no more than the cap.
      const double v0 = head_velocity_[a];
      head_velocity_[a] = std::clamp(v0 + accel * h, -head_speed_cap_[a], head_speed_cap_[a]);
      head_[a] += 0.5 * (v0 + head_velocity_[a]) * h;
    }
  }
}

void GazeGenerator::sample(double t, std::span<double> frame) noexcept {
  if (!started_) {
    started_ = true;
    head_t_ = t;
    // A first fixation at the centre before the first saccade.
    next_saccade_ = t + random_.uniform(spec_.fixation_min, spec_.fixation_max);
  }
  if (t >= next_saccade_) begin_saccade(t);
  const double progress = saccade_s_ > 0 ? min_jerk((t - saccade_start_) / saccade_s_) : 1.0;
  for (std::size_t k = 0; k < 3; ++k) gaze_[k] = from_[k] + progress * (to_[k] - from_[k]);
  follow_head(t);

  const auto put = [&](const std::optional<std::size_t>& channel, double about_rest) {
    if (!channel) return;
    const IdleChannelLimits& l = limits_[*channel];
    frame[*channel] = std::clamp(l.rest + about_rest, l.low(), l.high());
  };
  if (spec_.look_at) {
    put(spec_.head_pan, head_[0] * head_scale_[0]);
    put(spec_.head_tilt, head_[1] * head_scale_[1]);
    return;
  }
  const double head_pan = spec_.head_pan ? head_[0] : 0.0;
  const double head_tilt = spec_.head_tilt ? head_[1] : 0.0;
  put(spec_.eyes_pan, gaze_[0] - head_pan);
  put(spec_.left_pan, gaze_[0] - gaze_[2] - head_pan);
  put(spec_.right_pan, gaze_[0] + gaze_[2] - head_pan);
  put(spec_.eyes_tilt, gaze_[1] - head_tilt);
  put(spec_.head_pan, head_[0]);
  put(spec_.head_tilt, head_[1]);
}

}  // namespace avar::playback
