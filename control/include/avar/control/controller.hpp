#pragma once
// The control loop's tick: sample the show -> limit -> finite check -> hand the frame to the
// links, inside a small state machine that eases in from the present pose (homing), plays
// (running), eases out to rest (stopping) and ends (finished), with one path to the safe state
// on any fault. Construction allocates; tick() is real-time safe: no allocation, exception,
// lock, string lookup or logging. One thread calls tick(); request_stop() may come from the
// same thread (the runner polls the signal flag and forwards it).

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "avar/control/limiter.hpp"
#include "avar/control/ramp.hpp"
#include "avar/control/rig.hpp"
#include "avar/core/status.hpp"
#include "avar/firmware_iface/actuator_link.hpp"
#include "avar/playback/sampler.hpp"
#include "avar/playback/show.hpp"

namespace avar::control {

enum class Phase { idle, homing, running, stopping, finished };

const char* to_string(Phase p) noexcept;

/// Why the loop left the normal path. Latched until the controller is rebuilt.
enum class FaultCause { none, non_finite_command, link_failure };

const char* to_string(FaultCause c) noexcept;

struct Fault {
  FaultCause cause = FaultCause::none;
  Status status = Status::ok;
  std::size_t index = 0;  ///< channel (non-finite) or link (link failure)
  double time_s = 0;      ///< loop time at which it was detected
};

/// The stages of a tick whose cost is measured.
enum class Stage { sample, limit, send };
inline constexpr std::size_t kStageCount = 3;
const char* to_string(Stage s) noexcept;

/// Cost of one stage: the last tick's and the worst so far, in nanoseconds.
struct StageTime {
  std::int64_t last_ns = 0;
  std::int64_t worst_ns = 0;
};

/// Reads CLOCK_MONOTONIC in nanoseconds. Real-time safe.
std::int64_t monotonic_ns() noexcept;

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
};

class Controller {
 public:
  /// Binds the show's tracks to the rig's channels (names resolved here, once). The show must
  /// already be validated against the rig (config::check_show_against_rig); a track whose
  /// channel is missing throws std::invalid_argument. Links are borrowed and must outlive this.
  Controller(const Rig& rig, const playback::Show& show, std::vector<firmware_iface::ActuatorLink*> links,
             ControllerOptions options = {});

  /// Starts the soft start at loop time now_s from start_pose (where the figure is: the
  /// devices' reported positions, or the rest pose where unknown).
  void begin(double now_s, std::span<const double> start_pose) noexcept;

  /// One tick at loop time now_s. Its period must be options.tick_period_s. Returns the status
  /// of this tick's sends.
  Status tick(double now_s) noexcept;

  /// Eases to rest from wherever the figure is, then finishes. Idempotent.
  void request_stop(double now_s) noexcept;

  /// Releases every actuator at once (second Ctrl-C) and finishes.
  void release_now() noexcept;

  Phase phase() const noexcept { return phase_; }
  const Fault& fault() const noexcept { return fault_; }
  bool stop_requested() const noexcept { return stop_requested_; }
  /// Show time of the last running tick (seconds into the show, growing across loops).
  double show_time() const noexcept { return show_time_; }
  double show_duration() const noexcept { return show_.duration; }
  /// Loop time at which the show started playing (after the soft start), or -1.
  double show_start_time() const noexcept { return show_start_; }
  /// The frame that the last tick sent (after limits), indexed by channel.
  std::span<const double> commanded() const noexcept { return commanded_; }
  /// The frame that the last tick asked for before limits.
  std::span<const double> target() const noexcept { return target_; }
  const Limiter& limiter() const noexcept { return limiter_; }
  const StageTime& stage_time(Stage s) const noexcept { return stage_times_[static_cast<std::size_t>(s)]; }
  std::size_t channel_count() const noexcept { return rig_.channels.size(); }
  double tick_period() const noexcept { return options_.tick_period_s; }

 private:
  void start_stopping(double now_s) noexcept;
  /// Closes the stage that began at *mark and opens the next one at the same instant.
  void lap(Stage s, std::int64_t& mark) noexcept;
  bool show_over(double show_time_s) const noexcept;

  const Rig& rig_;
  const playback::Show& show_;
  std::vector<firmware_iface::ActuatorLink*> links_;
  ControllerOptions options_;
  playback::Sampler sampler_;
  Limiter limiter_;
  Ramp ramp_;
  std::vector<double> rest_;
  std::vector<double> ramp_velocity_;
  std::vector<double> first_frame_;
  std::vector<double> target_;
  std::vector<double> commanded_;
  std::vector<double> heading_;
  std::vector<char> link_dead_;
  std::array<StageTime, kStageCount> stage_times_{};
  Phase phase_ = Phase::idle;
  Fault fault_;
  bool stop_requested_ = false;
  double phase_start_ = 0;
  double show_start_ = -1;
  double show_time_ = 0;
};

}  // namespace avar::control
