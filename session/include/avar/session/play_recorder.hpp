#pragma once
// Watches a play run tick by tick, and only watches: accumulates tracking statistics, keeps the
// samples a trace or plot needs, and draws the progress line. Nothing in the loop depends on it.
// Positions and device reports are the controller's own (Controller::measured() and
// telemetry(): the simulator's ground truth where there is one, the devices' reports
// elsewhere). What a tick reads answers the tick before, so each row's measured position and
// reports are those the next tick read; the last row's position stays unknown (NaN).

#include <cstdint>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "avar/control/live_inputs.hpp"
#include "avar/control/runner.hpp"
#include "avar/assembly/figure_links.hpp"
#include "avar/session/tracking_stats.hpp"

namespace avar::session {

struct PhaseMark {
  double time_s;
  control::Phase phase;
};

class PlayRecorder final : public control::TickObserver {
 public:
  /// keep_samples: store every tick for a trace or plot (sized for expected_ticks up front).
  /// progress: nullptr for none; otherwise the stream and whether it is a terminal. notices:
  /// where to say that a stop was requested (nullptr for nowhere).
  PlayRecorder(const assembly::FigureLinks& figure, std::size_t channels, bool keep_samples, std::size_t expected_ticks,
               std::ostream* progress, bool progress_is_terminal, std::ostream* notices);

  /// Also keep every live control's value per tick (with kept samples); borrowed, nullptr: none.
  void watch(const control::LiveInputs* live) { live_ = live; }

  void after_tick(std::uint64_t tick, double now_s, double dt_s, double lateness_s, control::Controller& controller) override;
  /// Ends the progress line.
  void finish();

  const TrackingStats& stats() const { return stats_; }
  const std::vector<PhaseMark>& phases() const { return phases_; }
  bool has_measurements() const { return has_measurements_; }

  // Samples, when kept: one row per tick, channel-major blocks of `channels` values.
  const std::vector<double>& seconds() const { return seconds_; }
  const std::vector<double>& targets() const { return targets_; }
  const std::vector<double>& commands() const { return commands_; }
  const std::vector<double>& measured() const { return measured_rows_; }  ///< NaN when unknown
  const std::vector<control::Phase>& phase_per_tick() const { return phase_rows_; }
  const std::vector<double>& lateness() const { return lateness_rows_; }  ///< seconds, per tick
  /// Stage costs per tick, kStageCount values a tick, nanoseconds.
  const std::vector<std::int64_t>& stage_ns() const { return stage_rows_; }
  /// Device telemetry per tick, `channels` entries a tick (the newest report at that tick).
  const std::vector<firmware_iface::ChannelTelemetry>& telemetry() const { return telemetry_rows_; }
  /// Live controls' raw values per tick (NaN before a control first moved), one block of
  /// LiveInputs::mailbox().size() values a tick.
  const std::vector<double>& controls() const { return control_rows_; }
  /// Wire counters per tick, one entry per link a tick.
  const std::vector<firmware_iface::LinkCounters>& link_counters() const { return counter_rows_; }

 private:
  void draw_progress(double now_s, const control::Controller& controller);
  /// Pairs what this tick read with the previous tick's command: statistics and the last row.
  void take_answer(const control::Controller& controller);

  const assembly::FigureLinks& figure_;
  std::size_t channels_;
  bool keep_samples_;
  std::ostream* progress_;
  bool terminal_;
  std::ostream* notices_;
  bool stop_announced_ = false;
  TrackingStats stats_;
  std::unique_ptr<bool[]> known_;
  std::vector<double> previous_command_;  ///< the last tick's command, for the next tick's answer
  bool previous_ready_ = false;
  bool has_measurements_ = false;
  std::vector<PhaseMark> phases_;
  double next_progress_s_ = 0;
  std::vector<double> seconds_, targets_, commands_, measured_rows_, lateness_rows_;
  std::vector<control::Phase> phase_rows_;
  std::vector<std::int64_t> stage_rows_;
  std::vector<firmware_iface::ChannelTelemetry> telemetry_rows_;
  std::vector<firmware_iface::LinkCounters> counter_rows_;
  const control::LiveInputs* live_ = nullptr;
  std::vector<double> control_rows_;
};

}  // namespace avar::session
