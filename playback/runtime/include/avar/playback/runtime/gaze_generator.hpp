#pragma once
// Gaze over time (GazeSpec): fixations, saccades on the main sequence, a head that follows after
// a delay, vergence for near targets (per-eye pan offsets, or with look_at the eyes aimed at a
// point through a GazeAim). Construction allocates; sample() is real-time safe. Times must not
// go back.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "avar/playback/runtime/behaviour_random.hpp"
#include "avar/playback/runtime/gaze_aim.hpp"
#include "avar/playback/runtime/idle_spec.hpp"

namespace avar::playback {

/// The main sequence: duration (s) of a saccade of `amplitude_deg` degrees, 21 ms + 2.2 ms/°.
double saccade_duration(double amplitude_deg) noexcept;

/// Share of an eye channel's limits a saccade may use; the head's counter-turn takes at most
/// kGazeHeadShare of the eye's velocity limit, so the eye never needs more than 95 %.
inline constexpr double kGazeSaccadeShare = 0.8;
inline constexpr double kGazeHeadShare = 0.15;

class GazeGenerator {
 public:
  GazeGenerator(const GazeSpec& spec, std::span<const IdleChannelLimits> limits, std::uint64_t seed);

  /// Writes the eye and head channels at time t (s) into frame; with look_at, the head channels
  /// only (aim_eyes writes the eyes).
  void sample(double t, std::span<double> frame) noexcept;
  /// Look-at gaze: the aim (when set) writes the eye channels that look at the point of the last
  /// sample, the figure posed as `frame` says (call it once the head is where it will be).
  void aim_eyes(std::span<double> frame) noexcept;

  /// Look-at gaze: what turns the gaze point into eye channels (borrowed; outlives this
  /// generator). Without one, look-at gaze moves the head only.
  void set_aim(GazeAim* aim) noexcept { aim_ = aim; }
  /// Look-at gaze: the point at the last sample.
  GazePoint gaze_point() const noexcept;

  /// The gaze (pan, tilt, vergence) at the last sample, channel units about rest (look_at: pan
  /// and tilt in degrees, the vergence as the target's inverse distance, 1/m).
  double gaze_pan() const noexcept { return gaze_[0]; }
  double gaze_tilt() const noexcept { return gaze_[1]; }
  /// The head (pan, tilt) at the last sample, gaze units about rest.
  double head_pan() const noexcept { return head_[0]; }
  double head_tilt() const noexcept { return head_[1]; }
  /// Saccades begun so far, and the last one's duration (s).
  std::uint64_t saccades() const noexcept { return saccades_; }
  double last_saccade_s() const noexcept { return saccade_s_; }
  /// The last saccade's amplitude (pan and tilt together), channel units.
  double last_amplitude() const noexcept { return amplitude_; }
  /// When the current saccade began and when the next one will (s).
  double saccade_start() const noexcept { return saccade_start_; }
  double next_saccade() const noexcept { return next_saccade_; }

 private:
  void begin_saccade(double t) noexcept;
  void follow_head(double t) noexcept;

  struct HeadGoal {
    double due = 0;
    double pan = 0, tilt = 0;
  };
  GazeSpec spec_;
  std::vector<IdleChannelLimits> limits_;
  BehaviourRandom random_;
  std::array<double, 3> from_{}, to_{}, gaze_{};  ///< pan, tilt, vergence (look_at: 1/distance)
  double saccade_start_ = 0, saccade_s_ = 0, next_saccade_ = 0, amplitude_ = 0;
  std::uint64_t saccades_ = 0;
  std::array<HeadGoal, 4> pending_{};  ///< head goals not yet due, oldest first
  std::size_t pending_count_ = 0;
  std::array<double, 2> head_goal_{}, head_{}, head_velocity_{};  ///< pan, tilt about rest
  std::array<double, 2> head_speed_cap_{}, head_accel_cap_{};
  std::array<double, 2> head_scale_{1, 1};  ///< head channel units per gaze unit
  GazeAim* aim_ = nullptr;
  double head_t_ = 0;
  bool started_ = false;
};

}  // namespace avar::playback
