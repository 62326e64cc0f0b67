#pragma once
// The control loop's tick and its supervisor. Every tick: read feedback (the links' device
// telemetry and, where there is one, a position source such as the simulator's ground truth;
// tracking, over-temperature and overload checks) -> sample the show -> inverse kinematics ->
// limit -> finite check -> hand the frame to the links. Around it, the supervisor's state
// machine (supervisor.hpp), whose fail-safe moves the controller drives.
//
// Homing glides from the present pose to the show's first frame (Limiter::glide_to:
// jerk-limited, all channels arriving together at rest), and the show starts there; stopping
// eases to rest. A fault (e-stop, link watchdog or failure, tracking error, non-finite command,
// device over-temperature or overload, deadline misses beyond the budget) is latched with its cause, where and when,
// and takes the single path to the safe state: every actuator does its fail-safe action from
// the rig (hold, ease to rest, or release) until reset() clears the fault.
//
// Construction allocates; tick() and the fault/stop entry points are real-time safe: no
// allocation, exception, lock, string lookup or logging. One thread drives the controller.

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "avar/control/ik_stage.hpp"
#include "avar/control/target_aims.hpp"
#include "avar/control/limiter.hpp"
#include "avar/control/live_layer.hpp"
#include "avar/control/plant.hpp"
#include "avar/control/ramp.hpp"
#include "avar/control/show_clock.hpp"
#include "avar/control/supervisor.hpp"
#include "avar/rig/rig.hpp"
#include "avar/core/monotonic_clock.hpp"
#include "avar/core/status.hpp"
#include "avar/firmware_iface/actuator_link.hpp"
#include "avar/playback/runtime/sampler.hpp"
#include "avar/playback/runtime/show.hpp"

namespace avar::control {

/// The stages of a tick whose cost is measured.
enum class Stage { sample, ik, mix, limit, send };
inline constexpr std::size_t kStageCount = 5;
const char* to_string(Stage s) noexcept;

/// Cost of one stage: the last tick's and the worst so far, in nanoseconds.
struct StageTime {
  std::int64_t last_ns = 0;
  std::int64_t worst_ns = 0;
};

/// CLOCK_MONOTONIC in nanoseconds (avar/core/monotonic_clock.hpp). Real-time safe.
using avar::monotonic_ns;

struct ControllerOptions {
  /// How many passes of a looping show to play before stopping; 0 = until stopped.
  /// A show that does not loop plays once whatever this says.
  std::uint64_t loops = 0;
  /// Shortest soft start / soft stop, seconds.
  double min_ramp_s = 0.25;
  /// The tick period tick() will be called with (seconds); the limiter is sized for it.
  double tick_period_s = 0.02;
  /// Clock for stage timing only (the motion never depends on it); nullptr: no timing.
  std::int64_t (*stage_clock)() noexcept = monotonic_ns;
  /// Positions measured apart from the links (the simulator's ground truth, external encoders),
  /// read at the start of every tick; borrowed, must outlive the controller. nullptr: none.
  const PositionSource* positions = nullptr;
  /// Live inputs mixed over the show while it runs (after inverse kinematics, before the
  /// limiter); borrowed, must outlive the controller, called on the loop thread. nullptr: none.
  LiveLayer* live = nullptr;
  /// Seconds the running phase holds the show's first frame before it plays (lead-in) and its
  /// last frame after it ends (lead-out), with the live layers over it (idle life between
  /// shows). show_time() runs from -lead_in_s. >= 0.
  double lead_in_s = 0;
  double lead_out_s = 0;
  /// Show time while running (a timecode chase); borrowed, must outlive the controller, read on
  /// the loop thread. nullptr: loop time since the show started.
  ShowClock* show_clock = nullptr;
  /// Targets held by hand, solved for instead of the show's (TargetAims); borrowed, must outlive
  /// the controller, read on the loop thread. nullptr: none.
  const TargetAims* aims = nullptr;
};

/// A show bound to a rig's channels, ready for a controller to sample: its sampler and, when the
/// show has targets, its inverse-kinematics stage. Built off the loop thread (allocates, throws
/// as Controller's constructor does), then handed to Controller::swap_show on it. `keep` holds
/// the show alive where the binding owns it (a show edited while it plays); otherwise the show
/// is borrowed and must outlive the binding.
struct ShowBinding {
  ShowBinding(const rig::Rig& rig, const playback::Show& show, std::span<const double> rest_frame,
              std::shared_ptr<const playback::Show> keep = nullptr);
  std::shared_ptr<const playback::Show> keep;
  const playback::Show* show;
  playback::Sampler sampler;
  std::optional<IkStage> ik;  ///< when the show has targets for the rig's kinematics
};

class Controller {
 public:
  /// Binds the show's tracks to the rig's channels (names resolved here, once). The show must
  /// already be validated against the rig (config::check_show_against_rig); a track whose
  /// channel is missing throws std::invalid_argument. links[i] serves rig.links[i]; links are
  /// borrowed and must outlive the controller.
  Controller(const rig::Rig& rig, const playback::Show& show, std::vector<firmware_iface::ActuatorLink*> links,
             ControllerOptions options = {});

  /// Binds another show (validated against this controller's rig) for swap_show. Allocates and
  /// may throw (std::invalid_argument as the constructor); any thread, the controller is only
  /// read (its rig and rest pose).
  std::unique_ptr<ShowBinding> bind_show(std::shared_ptr<const playback::Show> show) const;

  /// Plays `next` from now on, in every phase, and hands the binding it replaces back in `next`
  /// (to be freed off the loop thread). Show time is not moved: the next tick samples the new
  /// show at the same time, and the limiter turns any jump in the frame into a glide. Real-time
  /// safe (pointer swaps; the new IK stage is seeded from the last command). Loop thread.
  void swap_show(std::unique_ptr<ShowBinding>& next) noexcept;

  /// disabled -> homing at loop time now_s, from start_pose (the devices' reported positions,
  /// or the rest pose where unknown). Ignored in any other state.
  void begin(double now_s, std::span<const double> start_pose) noexcept;

  /// One tick at loop time now_s (period: options.tick_period_s). A send that fails latches a
  /// link fault (latched_fault() says which link and why).
  void tick(double now_s) noexcept;

  /// homing/running -> stopping: ease to rest from wherever the figure is heading. Idempotent.
  void request_stop(double now_s) noexcept;

  /// Latches a fault (the first one wins; later ones are counted) and starts the fail-safe
  /// actions. Works from every state, disabled included (an e-stop while idle still latches).
  void fault(FaultCause cause, std::size_t index, double value, double now_s, Status status = Status::ok) noexcept;

  /// Every tick reads its own feedback: each link's telemetry (a position where a device
  /// reported one since the last tick), then ControllerOptions::positions, which has the last
  /// word where it knows a channel. The two calls below add feedback from elsewhere, for the
  /// next tick to check (the position source still wins over them where it knows).
  ///
  /// Position feedback for the tracking check: measured[channel] where known[channel].
  /// Checked against the last command on the next tick. Real-time safe.
  void feed_back(std::span<const double> measured, std::span<const bool> known) noexcept;

  /// Telemetry indexed by channel, as Link::read_telemetry gives it: each entry refreshed
  /// since the last call (its `updates` grew) feeds its position to the tracking check, and its
  /// device fault bits latch device_overheat / device_overload / device_error faults on that
  /// channel (value: temperature, load, or the fault bits), stamped with the last tick's time
  /// (the exchange that brought the report). Real-time safe.
  void feed_telemetry(std::span<const firmware_iface::ChannelTelemetry> telemetry) noexcept;

  /// After the run: reads the feedback a next tick would read first (where the figure stood
  /// after the last tick's command) into measured() and telemetry(), latching no fault. Not
  /// while ticks run.
  void read_final_feedback() noexcept;

  /// faulted -> disabled, clearing the latched fault, once the fail-safe motions are over.
  /// Returns false (and changes nothing) otherwise.
  bool reset() noexcept;

  /// Releases every actuator at once (second Ctrl-C) and disables the controller.
  void release_now() noexcept;

  /// True while the controller needs ticks: homing, running, stopping, or faulted with fail-safe
  /// motions still under way.
  bool active() const noexcept;

  Phase phase() const noexcept { return supervisor_.phase(); }
  const Fault& latched_fault() const noexcept { return supervisor_.latched_fault(); }
  std::uint64_t faults_seen() const noexcept { return supervisor_.faults_seen(); }
  const Supervisor& supervisor() const noexcept { return supervisor_; }
  bool stop_requested() const noexcept { return stop_requested_; }
  /// Show time of the last running tick (seconds into the show, growing across loops; negative
  /// during the lead-in).
  double show_time() const noexcept { return show_time_; }
  double show_duration() const noexcept { return binding_->show->duration; }
  /// Show time at which the show's last pass ends (before any lead-out); infinite for a show
  /// looping until stopped.
  double show_end() const noexcept;
  /// Loop time at which the show started playing (after the soft start), or -1.
  double show_start_time() const noexcept { return show_start_; }
  /// The frame that the last tick sent (after limits), indexed by channel.
  std::span<const double> commanded() const noexcept { return commanded_; }
  /// Per channel, the command that the device carries out as of the last tick: the last command,
  /// or for a channel on a link that plays its commands later (command_delay_s) the command of
  /// that many ticks before. The tracking check compares the next feedback with it.
  std::span<const double> tracking_reference() const noexcept { return reference_; }
  /// Each channel's newest device report, as the last tick read it from the links.
  std::span<const firmware_iface::ChannelTelemetry> telemetry() const noexcept { return telemetry_; }
  /// The position feedback the last tick read (ControllerOptions::positions where it knows, a
  /// device's report since the tick before elsewhere), indexed by channel, channel units; NaN
  /// where none came: where the figure stood after the previous tick's command. What the
  /// tracking check compared with that command.
  std::span<const double> measured() const noexcept { return feedback_; }
  /// Whether the show starts over at its end (Show::loop).
  bool show_loops() const noexcept { return binding_->show->loop; }
  /// The frame that the last tick asked for before limits.
  std::span<const double> target() const noexcept { return target_; }
  const Limiter& limiter() const noexcept { return limiter_; }
  /// The inverse-kinematics stage, when the show has targets; nullptr otherwise.
  const IkStage* ik() const noexcept { return binding_->ik ? &*binding_->ik : nullptr; }
  const StageTime& stage_time(Stage s) const noexcept { return stage_times_[static_cast<std::size_t>(s)]; }
  std::size_t channel_count() const noexcept { return rig_.channels.size(); }
  double tick_period() const noexcept { return options_.tick_period_s; }

 private:
  void ease_to(std::span<const double> goal, double now_s) noexcept;
  bool ramp_done(double now_s) const noexcept;
  bool show_over(double show_time_s) const noexcept;
  void lap(Stage s, std::int64_t& mark) noexcept;
  /// The tick's first stage: the position source, then every link's telemetry.
  /// `latch`: whether the device fault bits and lost devices latch faults (not after the run).
  void read_feedback(bool latch) noexcept;
  /// measured() from what read_feedback() found.
  void publish_feedback() noexcept;
  /// Keeps the tick's commands and sets each channel's tracking reference.
  void remember_commands() noexcept;
  void take_telemetry(std::span<const firmware_iface::ChannelTelemetry> telemetry, std::vector<std::uint64_t>& seen,
                      bool latch) noexcept;
  /// The show's frame at a show time: tracks, then inverse kinematics for the targets.
  void sample_show(double show_time_s, std::span<double> frame) noexcept;

  const rig::Rig& rig_;
  std::vector<firmware_iface::ActuatorLink*> links_;
  ControllerOptions options_;
  std::vector<double> rest_;
  std::unique_ptr<ShowBinding> binding_;  ///< the show being played; never null
  Limiter limiter_;
  Ramp ramp_;
  Supervisor supervisor_;
  std::vector<double> failsafe_goal_;  ///< per channel, filled when a fault starts
  std::vector<double> ramp_velocity_;
  std::vector<double> first_frame_;
  std::vector<double> target_;
  std::vector<double> commanded_;
  /// The last commands, for channels whose link plays them later: history_depth_ frames of the
  /// channels' commands (a ring, newest at history_head_), and each channel's delay in ticks.
  std::vector<double> history_;
  std::size_t history_depth_ = 1, history_head_ = 0;
  std::vector<std::size_t> delay_ticks_;
  std::vector<double> reference_;
  std::vector<double> heading_;
  std::vector<double> measured_;
  std::vector<char> measured_known_;
  std::vector<double> feedback_;                             ///< per channel: measured_ as the last tick read it, NaN: none
  std::vector<std::uint64_t> telemetry_seen_;                ///< per channel: `updates` at the last feed_telemetry
  std::vector<firmware_iface::ChannelTelemetry> telemetry_;  ///< per channel: the links' newest reports
  std::vector<std::uint64_t> link_telemetry_seen_;           ///< per channel: `updates` the tick took
  std::unique_ptr<bool[]> source_known_;                     ///< per channel: options.positions knew it
  std::array<StageTime, kStageCount> stage_times_{};
  bool begun_ = false;
  double last_now_ = 0;
  bool stop_requested_ = false;
  double phase_start_ = 0;
  double homing_duration_ = 0;  ///< of the soft start's glide, s
  double show_start_ = -1;
  double show_time_ = 0;
};

}  // namespace avar::control
