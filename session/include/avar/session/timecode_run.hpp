#pragma once
// Show time that chases a timecode source (`avar play ... --timecode SOURCE [--offset HH:MM:SS:FF]
// [--freewheel S]`): the options, the source they open, and the chase run around the play loop
// (its clock, per-tick trace columns, summary lines). Front ends parse the options; this opens
// and runs them.
//
// Sources: ltc:FILE.wav (LTC audio from a sound file, played in real time, or on the simulated
// clock with --fast), ltc:alsa:DEVICE (not built: see open_timecode_source), mtc:PORT (MIDI Time
// Code from an ALSA sequencer port, as `avar inputs` lists them), artnet, artnet:PORT or
// artnet:HOST:PORT (ArtTimeCode over UDP; host 127.0.0.1 and port 6454 unless told).

#include <cstdint>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "avar/control/chase_clock.hpp"
#include "avar/control/runner.hpp"
#include "avar/inputs/timecode_source.hpp"

namespace avar::session {

struct ShowControlOptions {
  std::optional<std::string> source;       ///< --timecode
  std::optional<std::string> offset;       ///< --offset HH:MM:SS:FF: source time at show time 0
  double freewheel_s = 2.0;                ///< --freewheel S
  std::optional<std::string> osc_control;  ///< --osc-control [ADDR:]PORT (osc_control.hpp)
};

/// Opens (does not start) the source `spec` names. `fast`: the run is on the simulated clock,
/// where only a file can play. Throws InputError-free std::invalid_argument with what was
/// expected for a malformed or unusable spec, std::runtime_error for a file that cannot be read.
std::unique_ptr<inputs::TimecodeSource> open_timecode_source(const std::string& spec, bool fast);

/// One column of numbers for the trace, one value a tick (NaN: empty cell).
struct TraceColumn {
  std::string name;
  std::vector<double> values;
};

/// The chase around one play run: owns the source and the chase clock, watches every tick
/// (forwarding to the run's own observer) and reports.
class TimecodeRun final : public control::TickObserver {
 public:
  /// Validates the options (std::invalid_argument naming what was expected) and opens the
  /// source; nothing is started.
  TimecodeRun(const ShowControlOptions& options, bool fast, std::size_t expected_ticks);
  ~TimecodeRun() override;

  /// Starts receiving (std::runtime_error when the device or socket cannot be opened).
  void start();
  void stop() noexcept;

  control::ShowClock& clock() { return *chase_; }
  /// Forward every tick to `inner` too (the run's recorder).
  void forward_to(control::TickObserver& inner) { inner_ = &inner; }
  void after_tick(std::uint64_t tick, double now_s, double dt_s, double lateness_s, control::Controller& controller) override;

  /// Lines for the play summary: the source and its counters, the chase error, how it ended.
  void summarize(std::ostream& out) const;
  /// show_time, chase_clock_s and chase_error_ms, one value per tick (empty when not running).
  std::vector<TraceColumn> trace_columns() const;
  /// True when the run ended because the source stopped (freewheel ran out).
  bool source_lost() const noexcept { return chase_->state() == control::ChaseState::stopped; }

 private:
  std::unique_ptr<inputs::TimecodeSource> source_;
  std::unique_ptr<control::ChaseClock> chase_;
  control::TickObserver* inner_ = nullptr;
  std::vector<double> show_time_, clock_s_, error_ms_;
};

}  // namespace avar::session
