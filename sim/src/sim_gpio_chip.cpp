#include "avar/sim/sim_gpio_chip.hpp"

#include <stdexcept>

#include "avar/inputs/atomic_input_counters.hpp"

namespace avar::sim {
namespace {

/// Edge times on the clock input devices stamp with (CLOCK_MONOTONIC).
std::int64_t monotonic_now_ns() noexcept { return inputs::input_arrival_now_ns(); }

}  // namespace

SimGpioChip::SimGpioChip(const std::string& name, unsigned lines)
    : describe_("simulated GPIO chip '" + name + "'"), lines_(lines) {}

SimGpioChip::Line& SimGpioChip::checked(unsigned line, const char* what) {
  if (line >= lines_.size())
    throw std::runtime_error(describe_ + " has " + std::to_string(lines_.size()) + " lines (0 to " +
                             std::to_string(lines_.size() - 1) + "); line " + std::to_string(line) + " does not exist");
  Line& l = lines_[line];
  if (l.requested)
    throw std::runtime_error(describe_ + ": cannot request line " + std::to_string(line) + " " + what +
                             ": it is in use (requested twice)");
  return l;
}

bool SimGpioChip::level_of(const Line& l) const noexcept {
  if (l.output) return l.driven;
  if (l.outside) return *l.outside;
  return l.bias == firmware_iface::GpioBias::pull_up;
}

void SimGpioChip::request_input(const firmware_iface::GpioInputRequest& request) {
  const std::lock_guard lock(mutex_);
  Line& l = checked(request.line, "as an input");
  l.requested = true;
  l.output = false;
  l.active_low = request.active_low;
  l.bias = request.bias;
  l.edge_events = request.edge_events;
}

void SimGpioChip::request_output(const firmware_iface::GpioOutputRequest& request) {
  const std::lock_guard lock(mutex_);
  Line& l = checked(request.line, "as an output");
  l.requested = true;
  l.output = true;
  l.active_low = request.active_low;
  l.edge_events = false;
  l.driven = request.initial != request.active_low;
  l.output_changes = 0;
}

void SimGpioChip::release(unsigned line) noexcept {
  const std::lock_guard lock(mutex_);
  if (line >= lines_.size()) return;
  Line& l = lines_[line];
  const std::optional<bool> outside = l.outside;
  l = Line{};
  l.outside = outside;
}

Status SimGpioChip::get(unsigned line, bool& value) noexcept {
  const std::lock_guard lock(mutex_);
  if (line >= lines_.size() || !lines_[line].requested) return Status::out_of_range;
  const Line& l = lines_[line];
  value = level_of(l) != l.active_low;
  return Status::ok;
}

Status SimGpioChip::set(unsigned line, bool value) noexcept {
  const std::lock_guard lock(mutex_);
  if (line >= lines_.size() || !lines_[line].requested || !lines_[line].output) return Status::out_of_range;
  Line& l = lines_[line];
  const bool level = value != l.active_low;
  if (level != l.driven) ++l.output_changes;
  l.driven = level;
  return Status::ok;
}

Status SimGpioChip::wait_edges(std::chrono::nanoseconds timeout, std::span<firmware_iface::GpioEdge> out,
                               std::size_t& count) noexcept {
  count = 0;
  std::unique_lock lock(mutex_);
  if (!edge_ready_.wait_for(lock, timeout, [&] { return !edges_.empty(); })) return Status::ok;
  while (count < out.size() && !edges_.empty()) {
    out[count++] = edges_.front();
    edges_.pop_front();
  }
  return Status::ok;
}

void SimGpioChip::note_edge(unsigned line, bool before) noexcept {
  const Line& l = lines_[line];
  const bool after = level_of(l) != l.active_low;
  if (!l.requested || l.output || !l.edge_events || after == before) return;
  if (edges_.size() >= kEdgeQueue) {
    edges_.pop_front();
    ++edges_dropped_;
  }
  edges_.push_back({line, after, monotonic_now_ns()});
  edge_ready_.notify_all();
}

void SimGpioChip::set_level(unsigned line, bool high) {
  const std::lock_guard lock(mutex_);
  Line& l = lines_.at(line);
  if (l.requested && l.output) return;
  const bool before = level_of(l) != l.active_low;
  l.outside = high;
  note_edge(line, before);
}

void SimGpioChip::float_line(unsigned line) {
  const std::lock_guard lock(mutex_);
  Line& l = lines_.at(line);
  const bool before = level_of(l) != l.active_low;
  l.outside.reset();
  note_edge(line, before);
}

bool SimGpioChip::level(unsigned line) const {
  const std::lock_guard lock(mutex_);
  return level_of(lines_.at(line));
}

std::uint64_t SimGpioChip::output_changes(unsigned line) const {
  const std::lock_guard lock(mutex_);
  return lines_.at(line).output_changes;
}

bool SimGpioChip::is_output(unsigned line) const {
  const std::lock_guard lock(mutex_);
  return lines_.at(line).requested && lines_.at(line).output;
}

bool SimGpioChip::is_requested(unsigned line) const {
  const std::lock_guard lock(mutex_);
  return lines_.at(line).requested;
}

std::uint64_t SimGpioChip::edges_dropped() const {
  const std::lock_guard lock(mutex_);
  return edges_dropped_;
}

}  // namespace avar::sim
