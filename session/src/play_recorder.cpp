#include "avar/session/play_recorder.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <ostream>
#include <span>
#include <string>

namespace avar::session {

PlayRecorder::PlayRecorder(const RecorderOptions& options)
    : options_(options),
      stats_(options.channels),
      measured_(options.channels, std::numeric_limits<double>::quiet_NaN()),
      known_(new bool[options.channels]()),
      previous_command_(options.channels, 0.0) {
  if (options_.keep_samples) {
    const std::size_t ticks = options_.expected_ticks;
    seconds_.reserve(ticks);
    lateness_rows_.reserve(ticks);
    stage_rows_.reserve(ticks * control::kStageCount);
    phase_rows_.reserve(ticks);
    targets_.reserve(ticks * options_.channels);
    commands_.reserve(ticks * options_.channels);
    measured_rows_.reserve(ticks * options_.channels);
    telemetry_rows_.reserve(ticks * options_.channels);
    counter_rows_.reserve(ticks * options_.links);
    control_rows_.reserve(ticks * options_.controls);
  }
}

namespace {

/// A channel's device report as a record carries it (the position is the trace's measured).
firmware_iface::ChannelTelemetry reported(const ChannelRecord& c) {
  firmware_iface::ChannelTelemetry t;
  t.position = c.measured;
  t.load = c.load;
  t.temperature_c = c.temperature_c;
  t.faults = c.device_faults;
  return t;
}

}  // namespace

void PlayRecorder::on_tick(const TickRecord& r) {
  const std::size_t n = options_.channels;
  // What this tick read is where the figure stood after the previous tick's command: it answers
  // the row before this one.
  // (A tick whose record the ring dropped leaves its successor's reading unpaired.)
  if (previous_ready_ && r.tick == previous_tick_ + 1) {
    for (std::size_t c = 0; c < n; ++c) measured_[c] = r.channels[c].measured;
    take_answer(measured_);
    if (options_.keep_samples && !seconds_.empty())
      for (std::size_t c = 0; c < n; ++c) telemetry_rows_[(seconds_.size() - 1) * n + c] = reported(r.channels[c]);
  }
  for (std::size_t c = 0; c < n; ++c) previous_command_[c] = r.channels[c].reference;
  previous_ready_ = true;
  previous_tick_ = r.tick;

  if (phases_.empty() || phases_.back().phase != r.phase) phases_.push_back({r.now_s, r.phase});
  if (r.stop_requested && !stop_announced_) {
    stop_announced_ = true;
    if (options_.progress && options_.progress_is_terminal) *options_.progress << '\n';
    if (options_.notices)
      *options_.notices << "interrupt: easing to rest; interrupt again to release every servo at once" << std::endl;
  }

  if (options_.keep_samples) {
    seconds_.push_back(r.now_s);
    lateness_rows_.push_back(r.lateness_s);
    stage_rows_.insert(stage_rows_.end(), r.stage_ns.begin(), r.stage_ns.end());
    phase_rows_.push_back(r.phase);
    for (const ChannelRecord& c : r.channels) targets_.push_back(c.target);
    for (const ChannelRecord& c : r.channels) commands_.push_back(c.command);
    // Until the next record answers: no position, and the reports as this tick read them.
    measured_rows_.insert(measured_rows_.end(), n, std::numeric_limits<double>::quiet_NaN());
    for (const ChannelRecord& c : r.channels) telemetry_rows_.push_back(reported(c));
    counter_rows_.insert(counter_rows_.end(), r.links.begin(), r.links.end());
    control_rows_.insert(control_rows_.end(), r.controls.begin(), r.controls.end());
  }
  if (options_.progress && r.now_s >= next_progress_s_) {
    draw_progress(r);
    next_progress_s_ = r.now_s + (options_.progress_is_terminal ? 0.2 : 2.0);
  }
}

void PlayRecorder::take_answer(std::span<const double> measured) {
  const std::size_t n = options_.channels;
  const std::span<bool> known(known_.get(), n);
  for (std::size_t c = 0; c < n; ++c) {
    known[c] = !std::isnan(measured[c]);
    has_measurements_ = has_measurements_ || known[c];
  }
  stats_.add(previous_command_, measured, known);
  if (!options_.keep_samples || seconds_.empty()) return;
  std::copy(measured.begin(), measured.begin() + static_cast<std::ptrdiff_t>(n),
            measured_rows_.begin() + static_cast<std::ptrdiff_t>((seconds_.size() - 1) * n));
}

void PlayRecorder::draw_progress(const TickRecord& r) {
  const double duration = options_.show_duration_s;
  const double show_t = r.phase == control::Phase::running ? r.show_time_s : 0.0;
  const double within = duration > 0 ? std::fmod(show_t, duration) : 0.0;
  const double fraction =
      r.phase == control::Phase::stopping || r.phase == control::Phase::disabled ? 1.0 : (duration > 0 ? within / duration : 0.0);
  constexpr int kWidth = 24;
  const auto filled = static_cast<int>(std::lround(fraction * kWidth));
  char line[160];
  if (std::isfinite(duration))
    std::snprintf(line, sizeof line, "%-8s show %6.2f / %.2f s  [%-*s] %3d%%  loop time %7.2f s", control::to_string(r.phase),
                  within, duration, kWidth, std::string(static_cast<std::size_t>(filled), '#').c_str(),
                  static_cast<int>(std::lround(fraction * 100)), r.now_s);
  else  // live only: no show to measure against
    std::snprintf(line, sizeof line, "%-8s live %8.2f s  loop time %7.2f s", control::to_string(r.phase), show_t, r.now_s);
  if (options_.progress_is_terminal) *options_.progress << '\r' << line << "\033[K" << std::flush;
  else *options_.progress << line << '\n' << std::flush;
}

void PlayRecorder::finish(const control::Controller& controller) {
  if (previous_ready_) {
    take_answer(controller.measured());
    if (options_.keep_samples && !seconds_.empty())
      std::copy(controller.telemetry().begin(), controller.telemetry().end(),
                telemetry_rows_.begin() + static_cast<std::ptrdiff_t>((seconds_.size() - 1) * options_.channels));
    previous_ready_ = false;
  }
  if (options_.progress && options_.progress_is_terminal) *options_.progress << '\n' << std::flush;
}

}  // namespace avar::session
