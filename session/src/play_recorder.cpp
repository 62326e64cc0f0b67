#include "avar/session/play_recorder.hpp"

#include <cmath>
#include <cstdio>
#include <iomanip>
#include <limits>
#include <ostream>
#include <span>

namespace avar::session {

PlayRecorder::PlayRecorder(const assembly::FigureLinks& figure, std::size_t channels, bool keep_samples,
                           std::size_t expected_ticks, std::ostream* progress, bool progress_is_terminal, std::ostream* notices)
    : figure_(figure),
      channels_(channels),
      keep_samples_(keep_samples),
      progress_(progress),
      terminal_(progress_is_terminal),
      notices_(notices),
      stats_(channels),
      known_(new bool[channels]()),
      previous_command_(channels, 0.0) {
  if (keep_samples_) {
    seconds_.reserve(expected_ticks);
    lateness_rows_.reserve(expected_ticks);
    stage_rows_.reserve(expected_ticks * control::kStageCount);
    phase_rows_.reserve(expected_ticks);
    targets_.reserve(expected_ticks * channels);
    commands_.reserve(expected_ticks * channels);
    measured_rows_.reserve(expected_ticks * channels);
    telemetry_rows_.reserve(expected_ticks * channels);
    counter_rows_.reserve(expected_ticks * figure_.link_count());
  }
}

void PlayRecorder::after_tick(std::uint64_t, double now_s, double, double lateness_s, control::Controller& controller) {
  // What the controller read at this tick's start is where the figure stood after the previous
  // tick's command: it answers the row before this one.
  if (previous_ready_) take_answer(controller);
  previous_command_.assign(controller.commanded().begin(), controller.commanded().end());
  previous_ready_ = true;

  if (phases_.empty() || phases_.back().phase != controller.phase()) phases_.push_back({now_s, controller.phase()});
  if (controller.stop_requested() && !stop_announced_) {
    stop_announced_ = true;
    if (progress_ && terminal_) *progress_ << '\n';
    if (notices_) *notices_ << "interrupt: easing to rest; interrupt again to release every servo at once" << std::endl;
  }

  if (keep_samples_) {
    seconds_.push_back(now_s);
    lateness_rows_.push_back(lateness_s);
    for (std::size_t s = 0; s < control::kStageCount; ++s)
      stage_rows_.push_back(controller.stage_time(static_cast<control::Stage>(s)).last_ns);
    phase_rows_.push_back(controller.phase());
    const auto target = controller.target();
    const auto command = controller.commanded();
    targets_.insert(targets_.end(), target.begin(), target.end());
    commands_.insert(commands_.end(), command.begin(), command.end());
    // Until the next tick answers: no position, and the reports as this tick read them.
    measured_rows_.insert(measured_rows_.end(), channels_, std::numeric_limits<double>::quiet_NaN());
    telemetry_rows_.insert(telemetry_rows_.end(), controller.telemetry().begin(), controller.telemetry().end());
    for (std::size_t l = 0; l < figure_.link_count(); ++l) counter_rows_.push_back(figure_.counters(l));
    if (live_) control_rows_.insert(control_rows_.end(), live_->control_values().begin(), live_->control_values().end());
  }
  if (progress_ && now_s >= next_progress_s_) {
    draw_progress(now_s, controller);
    next_progress_s_ = now_s + (terminal_ ? 0.2 : 2.0);
  }
}

void PlayRecorder::take_answer(const control::Controller& controller) {
  const std::span<const double> measured = controller.measured();
  const std::span<bool> known(known_.get(), channels_);
  for (std::size_t c = 0; c < channels_; ++c) {
    known[c] = !std::isnan(measured[c]);
    has_measurements_ = has_measurements_ || known[c];
  }
  stats_.add(previous_command_, measured, known);
  if (!keep_samples_ || seconds_.empty()) return;
  const std::size_t row = (seconds_.size() - 1) * channels_;
  std::copy(measured.begin(), measured.end(), measured_rows_.begin() + static_cast<std::ptrdiff_t>(row));
  std::copy(controller.telemetry().begin(), controller.telemetry().end(),
            telemetry_rows_.begin() + static_cast<std::ptrdiff_t>(row));
}

void PlayRecorder::draw_progress(double now_s, const control::Controller& controller) {
  const double duration = controller.show_duration();
  const double show_t = controller.phase() == control::Phase::running ? controller.show_time() : 0.0;
  const double within = duration > 0 ? std::fmod(show_t, duration) : 0.0;
  const double fraction = controller.phase() == control::Phase::stopping || controller.phase() == control::Phase::disabled
                              ? 1.0
                              : (duration > 0 ? within / duration : 0.0);
  constexpr int kWidth = 24;
  const auto filled = static_cast<int>(std::lround(fraction * kWidth));
  char line[160];
  if (std::isfinite(duration))
    std::snprintf(line, sizeof line, "%-8s show %6.2f / %.2f s  [%-*s] %3d%%  loop time %7.2f s",
                  control::to_string(controller.phase()), within, duration, kWidth,
                  std::string(static_cast<std::size_t>(filled), '#').c_str(), static_cast<int>(std::lround(fraction * 100)),
                  now_s);
  else  // live only: no show to measure against
    std::snprintf(line, sizeof line, "%-8s live %8.2f s  loop time %7.2f s", control::to_string(controller.phase()), show_t,
                  now_s);
  if (terminal_) *progress_ << '\r' << line << "\033[K" << std::flush;
  else *progress_ << line << '\n' << std::flush;
}

void PlayRecorder::finish() {
  if (progress_ && terminal_) *progress_ << '\n' << std::flush;
}

}  // namespace avar::session
