#pragma once
// The timecode chase: show time that follows a timecode source through a phase-locked clock.
//
// Each running tick reads the clock (CLOCK_MONOTONIC for live sources; the loop time for a
// stepped source) and the source's newest position with its arrival time. The source's time now
// is that position extrapolated at play speed since it arrived. The chase clock runs at a filtered
// rate and is pulled toward it: a second-order loop (phase gain alpha, rate gain alpha^2/4 per
// new position: critically damped) that smooths the arrivals' jitter and follows a source whose
// speed differs a little from the machine's clock.
//
// - A new position further than jump_s from the chase clock relocks at once (the source jumped,
//   was located, or first appeared): show time jumps, and the limiter turns the jump into a
//   limited motion, never a snap.
// - A position that repeats (a paused sender) is not new.
// - With no new position for freewheel_s, the run stops (ease to rest); until then the clock
//   freewheels at its filtered rate.
// - Before the first position, and while the source is before the offset, show time holds at 0
//   (the show's first frame, where homing left the figure).
//
// Show time = chase clock - offset_s. Chase error = chase clock - source time now, measured on
// every tick that has a position no older than freewheel detection (2.5 frames); its |value| is
// kept in a histogram (1 µs buckets).
//
// Construction allocates; read() and the accessors are real-time safe. Loop thread only.

#include <cstdint>
#include <optional>

#include "avar/control/latency_histogram.hpp"
#include "avar/control/show_clock.hpp"
#include "avar/inputs/timecode_source.hpp"

namespace avar::control {

struct ChaseOptions {
  double offset_s = 0;  ///< source time at show time 0, s
  /// When set, the offset is this label, read at the source's rate when the first position
  /// arrives (replacing offset_s); frames beyond that rate's count are frames / fps.
  std::optional<Timecode> offset_label;
  double freewheel_s = 2.0;  ///< run on this long after the last new position, then stop
  double jump_s = 0.1;       ///< a difference larger than this relocks at once (a jump)
  double alpha = 0.15;       ///< phase gain per new position (0..1]
};

enum class ChaseState { waiting, locked, freewheeling, stopped };
const char* to_string(ChaseState s) noexcept;

class ChaseClock final : public ShowClock {
 public:
  /// `clock_ns`: the clock the source stamps arrivals with (monotonic_ns for live sources);
  /// nullptr: the source is stepped and its clock is the loop time. The source is borrowed.
  ChaseClock(inputs::TimecodeSource& source, ChaseOptions options, std::int64_t (*clock_ns)() noexcept);

  ShowClockReading read(double now_s) noexcept override;

  ChaseState state() const noexcept { return state_; }
  /// The clock reading of the last read(), seconds (monotonic or loop time).
  double last_clock_s() const noexcept { return clock_s_; }
  /// The last tick's chase error (chase clock - source time), s; NaN when not measured.
  double last_error_s() const noexcept { return error_s_; }
  /// Source seconds of the chase clock at the last read (before the offset).
  double chase_time_s() const noexcept { return phase_s_; }
  double rate() const noexcept { return rate_; }
  std::uint64_t jumps() const noexcept { return jumps_; }
  /// |chase error| of every measured tick.
  const LatencyHistogram& errors() const noexcept { return errors_; }
  /// The signed error of the largest magnitude, s.
  double worst_error_s() const noexcept { return worst_s_; }
  const ChaseOptions& options() const noexcept { return options_; }

 private:
  inputs::TimecodeSource& source_;
  ChaseOptions options_;
  std::int64_t (*clock_ns_)() noexcept;
  ChaseState state_ = ChaseState::waiting;
  std::uint64_t seen_sequence_ = 0;
  double last_position_s_ = 0;  ///< the last new position's seconds (to spot repeats)
  double fresh_at_s_ = 0;       ///< clock time of the last new position's arrival
  double frame_s_ = 0.04;       ///< the source's frame period
  double phase_s_ = 0;          ///< chase clock (source seconds) at clock_s_
  double rate_ = 1;             ///< chase clock seconds per clock second
  double clock_s_ = 0;
  double update_at_s_ = 0;  ///< clock time of the last loop update
  double error_s_ = 0;
  double worst_s_ = 0;
  std::uint64_t jumps_ = 0;
  LatencyHistogram errors_;
};

}  // namespace avar::control
