#pragma once
// Watches a play run record by record, and only watches: a SessionObserver that accumulates
// tracking statistics, keeps the samples a trace or plot needs, and draws the progress line, on
// the session's publisher thread (the loop's caller on the stepped clock). Nothing in the loop
// waits for it.
//
// Positions and device reports are the controller's own (TickRecord's measured, temperature,
// load and faults: the simulator's ground truth where there is one, the devices' reports
// elsewhere). What a tick reads answers the tick before, so each row's measured position and
// reports are those of the next record, and the last row's those the controller read after the
// run (finish()). In real time a record the ring dropped is a row missing, and its neighbour's
// position unknown (ShowSession::records_dropped()).

#include <cstdint>
#include <iosfwd>
#include <memory>
#include <span>
#include <vector>

#include "avar/control/controller.hpp"
#include "avar/session/tick_record.hpp"
#include "avar/session/tracking_stats.hpp"

namespace avar::session {

struct PhaseMark {
  double time_s;
  control::Phase phase;
};

struct RecorderOptions {
  std::size_t channels = 0;
  std::size_t links = 0;
  std::size_t controls = 0;    ///< live controls each record carries (SessionConfig::recorded_controls)
  double show_duration_s = 0;  ///< for the progress line; infinite for a live run without end
  /// Store every tick for a trace, plot or take (sized for expected_ticks up front).
  bool keep_samples = false;
  std::size_t expected_ticks = 0;
  std::ostream* progress = nullptr;   ///< where to draw the progress line; nullptr: nowhere
  bool progress_is_terminal = false;  ///< redraw one line (else a line every 2 s)
  std::ostream* notices = nullptr;    ///< where to say that a stop was requested; nullptr: nowhere
};

class PlayRecorder final : public SessionObserver {
 public:
  explicit PlayRecorder(const RecorderOptions& options);

  void on_tick(const TickRecord& record) override;
  /// After the run: answers the last row with what the controller read after it
  /// (ShowSession::run() has it read), and ends the progress line.
  void finish(const control::Controller& controller);

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
  /// Live controls' raw values per tick (NaN before a control first moved), `controls` values a
  /// tick.
  const std::vector<double>& controls() const { return control_rows_; }
  /// Wire counters per tick, one entry per link a tick.
  const std::vector<firmware_iface::LinkCounters>& link_counters() const { return counter_rows_; }

 private:
  void draw_progress(const TickRecord& record);
  /// Pairs positions read (NaN: unknown) with the previous record's command: statistics and the
  /// measured positions of the last row kept.
  void take_answer(std::span<const double> measured);

  RecorderOptions options_;
  bool stop_announced_ = false;
  TrackingStats stats_;
  std::vector<double> measured_;
  std::unique_ptr<bool[]> known_;
  std::vector<double> previous_command_;  ///< the last record's command, for the next one's answer
  bool previous_ready_ = false;
  std::uint64_t previous_tick_ = 0;
  bool has_measurements_ = false;
  std::vector<PhaseMark> phases_;
  double next_progress_s_ = 0;
  std::vector<double> seconds_, targets_, commands_, measured_rows_, lateness_rows_;
  std::vector<control::Phase> phase_rows_;
  std::vector<std::int64_t> stage_rows_;
  std::vector<firmware_iface::ChannelTelemetry> telemetry_rows_;
  std::vector<firmware_iface::LinkCounters> counter_rows_;
  std::vector<double> control_rows_;
};

}  // namespace avar::session
