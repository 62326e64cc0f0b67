#pragma once
// What idle life does, channel by channel (resolved to frame indices at load time): smooth
// noise, blinks, gaze with saccades and a following head, breathing. Every value is in channel
// units and seconds; angles of gaze are taken in degrees (main sequence). The generators keep
// whatever this asks for inside each channel's limits (idle_generator.hpp).

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

namespace avar::playback {

/// A channel's limits as idle life needs them (the rig's, copied at load).
struct IdleChannelLimits {
  double min = 0, max = 1;                                      ///< hard range
  double soft_margin = 0;                                       ///< idle stays this far inside the range
  double rest = 0;                                              ///< idle life moves about this value
  double max_velocity = 0, max_acceleration = 0, max_jerk = 0;  ///< units/s, /s², /s³ (> 0)

  double low() const noexcept { return min + soft_margin; }
  double high() const noexcept { return max - soft_margin; }
};

/// Smooth noise on one channel: rest + amplitude × fractal gradient noise at `frequency`.
struct NoiseSpec {
  std::size_t channel = 0;
  double amplitude = 0;    ///< channel units, > 0 (clipped to the room about rest)
  double frequency = 0.2;  ///< lattice cells per second, > 0
  int octaves = 1;         ///< 1..8
};

struct BlinkLid {
  std::size_t channel = 0;
  double open = 0;    ///< value with the lid open (the channel's rest unless told)
  double closed = 0;  ///< value with the lid shut
};

/// Blinks of the lids together: a blink closes, holds, opens (minimum-jerk moves); blink events
/// start interval_min..interval_max apart (start to start, uniform); with probability
/// double_probability an event is a double blink (a second one double_gap_s after the first).
struct BlinkSpec {
  std::vector<BlinkLid> lids;
  double interval_min = 2, interval_max = 6;            ///< s, 0 < min <= max
  double double_probability = 0.1;                      ///< 0..1
  double double_gap_s = 0.08;                           ///< lids open between the two blinks of a double
  double close_s = 0.08, hold_s = 0.04, open_s = 0.14;  ///< stretched where a lid's limits need it
};

/// Look-at gaze, for a rig with kinematics: the eyes are effectors of the rig's kinematic model and
/// a gaze target is a point in the world, its direction drawn in the field (degrees: pan to the
/// left, tilt up, in the gaze frame below) and its distance far or near. Each eye is aimed at the
/// point through inverse kinematics (control::GazeLookAt) with the head where it is, so vergence
/// and the eyes' counter-turn come from the geometry. Everything here is resolved at load.
struct GazeLookAt {
  static constexpr std::size_t kOnBase = std::numeric_limits<std::size_t>::max();
  std::vector<std::size_t> effectors;       ///< the eyes: indices into the kinematic model's effectors
  std::array<double, 3> aim_axis{1, 0, 0};  ///< each eye's line of sight, in its effector frame
  /// The joint the eyes hang from (the head's), or kOnBase. The joints between it and the eye
  /// effectors are the eyes' own: the aim solves them alone, with the head where it is.
  std::size_t mount_joint = kOnBase;
  std::vector<std::size_t> eye_channels;  ///< channels of the eyes' own joints (the aim writes them)
  /// The gaze frame in the world (the model's base frame, m), at the rest pose: the midpoint of
  /// the eyes, straight ahead (the eyes' mean line of sight), left and up (the base's z made
  /// square to ahead). Targets are centre + distance × direction(pan, tilt).
  std::array<double, 3> centre{0, 0, 0}, ahead{1, 0, 0}, left{0, 1, 0}, up{0, 0, 1};
  double far_m = 2, near_m = 0.3;  ///< target distances, m, 0 < near <= far
  double half_interocular_m = 0;   ///< half the distance between the eyes at rest, m
  /// The eye joints' tightest velocity, acceleration and jerk limits in degrees of gaze (each
  /// joint's limit over its degrees per channel unit, divided by the largest parallax gain a near
  /// target gives); a saccade's duration is stretched within these.
  IdleChannelLimits eye_limits;
  std::array<double, 2> head_units_per_degree{1, 1};  ///< head pan, tilt channel units per degree of gaze (signed)
};

/// Gaze: a target in the field is fixated for fixation_min..max s, then a saccade (minimum jerk,
/// its duration from the main sequence 21 ms + 2.2 ms/° of amplitude, stretched so the eye
/// channels' velocity, acceleration and jerk stay within 80 % of their limits) moves the eyes to
/// the next. The head turns `head_follow` of the gaze after `head_delay_s`, smoothed (critically
/// damped, time constant head_smoothing_s), and the eyes counter-turn as it comes (eye = gaze −
/// head). With probability near_probability a target is near: left and right eyes converge by
/// `vergence` (channel units each). With look_at, the eyes are aimed through the rig's kinematics
/// instead (GazeLookAt): the field is in degrees, a near target is near_m away (probability
/// near_probability), the eye channels are not eyes_pan/left_pan/right_pan/eyes_tilt, and the
/// head turns `head_follow` of the gaze's angle (head_units_per_degree).
struct GazeSpec {
  std::optional<std::size_t> eyes_pan, eyes_tilt;  ///< both eyes on one channel each
  std::optional<std::size_t> left_pan, right_pan;  ///< per-eye pan, for vergence
  std::optional<std::size_t> head_pan, head_tilt;
  double pan_min = -20, pan_max = 20;  ///< field of gaze targets, eye channel units about rest
  double tilt_min = -8, tilt_max = 8;
  double fixation_min = 0.4, fixation_max = 2.5;  ///< s
  double head_follow = 0.5;                       ///< 0..1: share of the gaze the head takes
  double head_delay_s = 0.15;                     ///< head starts this long after the saccade
  double head_smoothing_s = 0.35;
  double near_probability = 0;  ///< 0..1
  double vergence = 0;          ///< per eye, channel units; left eye −, right eye + (turn inwards)
  std::optional<GazeLookAt> look_at;
};

/// Breathing: one slow cycle shared by its channels (rest − amplitude/2 · cos 2πφ), each cycle's
/// period drawn within period_s × (1 ± jitter).
struct BreathingChannel {
  std::size_t channel = 0;
  double amplitude = 0;  ///< peak to peak, channel units
};
struct BreathingSpec {
  std::vector<BreathingChannel> channels;
  double period_s = 4;
  double jitter = 0.1;  ///< 0..0.5
};

struct IdleSpec {
  std::vector<IdleChannelLimits> limits;  ///< one per frame channel
  std::vector<NoiseSpec> noise;
  std::optional<BlinkSpec> blinks;
  std::optional<GazeSpec> gaze;
  std::optional<BreathingSpec> breathing;
  /// Idle hands over to and from a show (and live inputs) over this long, eased.
  double crossfade_s = 0.8;
};

}  // namespace avar::playback
