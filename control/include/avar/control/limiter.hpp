#pragma once
// Per-channel motion limits applied to every command before it reaches a link.
//
// Each tick, each channel's target is clamped into its range less the soft margins (the goal),
// and the channel's exact state (position, velocity, acceleration) is advanced by one tick along
// the time-optimal jerk-limited profile from that state to rest at the goal (JerkProfile: jerk in
// {-J, 0, +J}, |a| <= A, |v| <= V). The commands are samples of one continuous motion that
// respects V, A and J, so their first, second and third differences over dt do too. The profile
// is re-planned from the current state every tick the goal moves, so a moving target is followed
// at once (with the lag the limits impose); a held target is reached on one optimal profile,
// exactly and at rest, followed without solving it again (re-planning would give it back): a
// rest-to-rest move of d takes d/V + V/A + A/J when it reaches V and A. A profile goes
// no further than its start's braking point (where braking at the limits comes to rest) or its
// goal; both start within [min, max], so from every state it produces braking stops within the
// range and no command leaves it (a last clamp absorbs rounding). Nothing is delayed: a target
// starts moving the command on the tick it arrives. Units: channel units and seconds.
// Single-threaded: one owner calls apply(). Sized once; apply() is real-time safe (no
// allocation, exception or lock) and bounded per channel: at most one plan, typically 1-6
// evaluations of a closed form, at most JerkProfile::kMaxEvaluations.
//
// A digital channel (a relay, a valve, an LED) does not move, it switches: its command is max
// while the target is at or above the middle of [min, max] and min below it, on the tick the
// target crosses, with no motion limits, margins, glides or intermediate values.

#include <cstdint>
#include <span>
#include <vector>

#include "avar/control/jerk_profile.hpp"
#include "avar/core/status.hpp"

namespace avar::control {

struct ChannelLimits {
  double min = 0;               ///< hard range, channel units
  double max = 1;               ///< > min
  double max_velocity = 1;      ///< units/s, > 0
  double max_acceleration = 1;  ///< units/s², > 0
  double max_jerk = 1;          ///< units/s³, > 0
  double soft_margin = 0;       ///< targets stay this far inside [min, max], units, >= 0
  /// Switches between min and max (see above); the motion limits and the margin are not used
  /// (any value, infinity included, is accepted).
  bool digital = false;
};

class Limiter {
 public:
  /// dt_s: the tick period every apply() will use. Throws std::invalid_argument for
  /// non-positive limits (of analog channels) or period, or max <= min.
  Limiter(std::vector<ChannelLimits> limits, double dt_s);

  /// Sets the present pose, at rest, and makes it every channel's goal. Values are clamped into
  /// range; non-finite ones keep the previous value.
  void reset(std::span<const double> pose) noexcept;

  /// One tick toward `target`: out[i] is the new command. A non-finite target keeps heading for
  /// that channel's previous goal and the call returns Status::not_finite. target and out may
  /// alias.
  Status apply(std::span<const double> target, std::span<double> out) noexcept;

  /// The shortest soft start from the present pose to `goal` (clamped like a target) that
  /// glide_to() can take, in seconds: at least min_duration_s, and long enough that every
  /// channel's glide keeps within its limits and its peak speed within peak_speed[channel]
  /// (units/s). A glide of d over T peaks at 2d/T in speed, 8d/T² in acceleration and has jerk
  /// ±32d/T³.
  double glide_duration(std::span<const double> goal, std::span<const double> peak_speed, double min_duration_s) const noexcept;

  /// Soft start: every channel at rest glides to goal[channel] (clamped like a target) in
  /// duration_s, all arriving together, on the smoothest rest-to-rest motion: jerk +J for a
  /// quarter of the time, -J for half, +J for the last quarter, with J = 32d/T³ for a distance d
  /// (never above the channel's jerk limit: a duration shorter than glide_duration() makes the
  /// channels it does not suit arrive late). It is the time-optimal profile under that lower
  /// jerk limit, so apply() with `goal` as the target plans it once and follows it. The lower
  /// limit lasts while the target stays on the goal; any other target ends
  /// the glide at once and the channel's own limits apply again (raising limits is safe from
  /// any state within them). Channels in motion, those already on their goal and digital ones
  /// (which switch on the next apply()) do not glide.
  void glide_to(std::span<const double> goal, double duration_s) noexcept;

  /// Brings the limiter into cache for its first apply() toward `target`, as the soft start's
  /// set-up does before the first tick: each channel at rest makes the plan apply() would and
  /// drops it. Changes no state, command or goal. Real-time safe.
  void warm(std::span<const double> target) noexcept;

  /// True when every channel's command has come to rest on its goal.
  bool settled() const noexcept;

  std::size_t size() const noexcept { return channels_.size(); }
  const ChannelLimits& limits(std::size_t channel) const noexcept { return channels_[channel].limits; }
  /// The commands of the last tick.
  std::span<const double> last() const noexcept { return last_; }
  /// Where the channel is going: the last finite target clamped into range less its margins.
  /// During a glide, where braking at the channel's own limits brings it to rest: a glide is
  /// the soft start's approach, not a pose to hold or to start another move from.
  double heading(std::size_t channel) const noexcept;
  /// True while the channel glides (see glide_to()).
  bool gliding(std::size_t channel) const noexcept { return channels_[channel].gliding; }
  /// The channel's exact motion at the last command (position = last()[channel]).
  const MotionState& state(std::size_t channel) const noexcept { return channels_[channel].state; }
  /// Samples whose target lay outside the range less its margins.
  std::uint64_t clamped(std::size_t channel) const noexcept { return channels_[channel].clamped; }
  /// Largest distance seen between the (clamped) target and the command of the same tick: how
  /// far the limits made the figure trail the show.
  double max_lag(std::size_t channel) const noexcept { return channels_[channel].max_lag; }
  /// The cost of the channel's plan in the last tick: evaluations of the profile's distance
  /// (0 when it was at rest on its goal, or followed its last plan toward a held goal). See
  /// JerkProfile::evaluations().
  int evaluations(std::size_t channel) const noexcept { return channels_[channel].evaluations; }

 private:
  struct Channel {
    ChannelLimits limits;
    JerkLimits jerk_limits;   ///< the channel's, or lower during a glide
    bool gliding = false;     ///< jerk_limits are a glide's, toward glide_goal
    double glide_goal = 0;
    double slack = 0;         ///< units: how far a long plan may end from its goal (PlanSlack)
    double goal = 0;          ///< clamped target
    bool goal_moved = false;  ///< the goal differs from the last tick's
    MotionState state;        ///< of the last command
    double peak_velocity = 0;  ///< of the last plan: the next plan's first guess
    PeakSensitivity sensitivity;  ///< of the last plan, from the state it led to
    double goal_step = 0;         ///< how far the goal moved this tick
    double previous_goal_step = 0;  ///< and the tick before
    double previous_peak = 0;  ///< of the plan before it
    double earlier_peak = 0;   ///< and of the plan before that
    double rest_origin = 0;     ///< where the channel last left rest
    double rest_direction = 0;  ///< and which way (+1 or -1)
    bool on_rest_curve = false;  ///< and its state is still on the start common to plans from there
    double elapsed = 0;        ///< s along the channel's last plan
    bool follows = false;      ///< that plan ends on the goal: a held goal follows it unsolved
    int planned_ticks = 0;     ///< consecutive ticks in motion (k: the last k peaks are recent)
    bool extrapolate = true;   ///< the peaks' extrapolation guessed the last plan's better than its predecessor
    std::uint64_t clamped = 0;
    double max_lag = 0;
    int evaluations = 0;
  };

  /// A target clamped into the range less the soft margins: the goal it makes.
  static double goal_of(const ChannelLimits& l, double target) noexcept;
  /// A digital channel's command for a target: min or max.
  static double switched(const ChannelLimits& l, double target) noexcept;
  static JerkLimits own_limits(const ChannelLimits& l) noexcept { return {l.max_velocity, l.max_acceleration, l.max_jerk}; }
  /// The peak velocity the channel's next plan tries first (see JerkProfile::plan's hint).
  static double first_guess(const Channel& c) noexcept;
  static double extrapolated_peak(const Channel& c) noexcept;
  /// Solves the channel's plan from its state toward its goal into `profile` and takes its
  /// first tick.
  void plan(Channel& c, JerkProfile& profile) noexcept;
  /// Takes `next` as the channel's state (clamped into range for rounding; a non-finite one
  /// stops the channel where it is).
  static void settle(Channel& c, const MotionState& next) noexcept;

  double dt_s_;
  /// Each channel's last plan (kept, not constructed per plan: zeroing one was a tenth of the
  /// limiter's cost).
  std::vector<JerkProfile> plans_;
  std::vector<Channel> channels_;
  std::vector<double> last_;
};

}  // namespace avar::control
