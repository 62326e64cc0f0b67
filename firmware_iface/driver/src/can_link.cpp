#include "avar/firmware_iface/can_link.hpp"

#include <algorithm>
#include <stdexcept>

namespace avar::firmware_iface {
namespace {

std::size_t outbox_capacity(const std::vector<std::unique_ptr<CanDrives>>& drives) {
  std::size_t n = 0;
  for (const auto& d : drives) n += d->max_tick_frames();
  return n;
}

}  // namespace

CanLink::CanLink(std::unique_ptr<FrameTransport> transport, std::vector<std::unique_ptr<CanDrives>> drives, CanLinkConfig config)
    : transport_(std::move(transport)),
      drives_(std::move(drives)),
      config_(std::move(config)),
      outbox_(outbox_capacity(drives_)),
      reconnector_(config_.reconnect_every) {
  if (!transport_) throw std::invalid_argument("a CAN link needs a transport");
  if (drives_.empty()) throw std::invalid_argument("a CAN link needs at least one drive set");
  if (config_.description.empty()) config_.description = "CAN bus on " + transport_->name();
}

Status CanLink::start() {
  start_problem_.clear();
  for (auto& d : drives_) {
    const Status s = d->start(*transport_);
    if (s != Status::ok) {
      start_problem_ = d->start_problem();
      if (s == Status::io_error) reconnector_.lost();
      return s;
    }
  }
  return Status::ok;
}

std::string CanLink::channel_problem(std::size_t channel) const {
  for (const auto& d : drives_)
    if (std::string p = d->channel_problem(channel); !p.empty()) return p;
  return {};
}

Status CanLink::read_positions(std::span<double> frame, std::span<bool> known) {
  Status result = Status::ok;
  for (auto& d : drives_)
    if (const Status s = d->read_positions(*transport_, frame, known); s != Status::ok && result == Status::ok) result = s;
  return result;
}

bool CanLink::dispatch(const CanFrame& f) noexcept {
  if (f.error) {
    ++stats_.error_frames;
    return (f.id & kCanErrorBusOff) == 0;
  }
  stats_.bits_received += static_cast<std::uint64_t>(can_frame_bits(f));
  for (auto& d : drives_)
    if (d->take(f)) {
      ++stats_.frames_taken;
      counters_.add(&LinkCounters::replies);
      return true;
    }
  ++stats_.frames_ignored;
  return true;
}

Status CanLink::drain() noexcept {
  CanFrame f;
  const std::chrono::nanoseconds now = transport_->now();
  for (;;) {
    const Status s = transport_->receive(&f, now);
    if (s == Status::timeout) return Status::ok;
    if (s != Status::ok) return s;
    if (!dispatch(f)) return Status::io_error;
  }
}

bool CanLink::replies_complete() const noexcept {
  return std::all_of(drives_.begin(), drives_.end(), [](const auto& d) { return d->replies_complete(); });
}

Status CanLink::collect() noexcept {
  const std::chrono::nanoseconds deadline = transport_->now() + config_.reply_timeout;
  CanFrame f;
  while (!replies_complete()) {
    const Status s = transport_->receive(&f, deadline);
    if (s == Status::timeout) return Status::ok;
    if (s != Status::ok) return s;
    if (!dispatch(f)) return Status::io_error;
  }
  // Replies that have already come from drives no longer waited for count this tick too.
  return drain();
}

Status CanLink::flush() noexcept {
  if (outbox_.size() == 0) return Status::ok;
  const FrameCounters before = transport_->counters();
  const Status s = transport_->send(outbox_.frames());
  const FrameCounters after = transport_->counters();
  counters_.add(&LinkCounters::bytes_sent, after.bytes_sent - before.bytes_sent);
  if (s == Status::ok) {
    stats_.frames_sent += outbox_.size();
    for (const CanFrame& f : outbox_.frames()) stats_.bits_sent += static_cast<std::uint64_t>(can_frame_bits(f));
  }
  outbox_.clear();
  return s;
}

Status CanLink::send(std::span<const double> frame) noexcept {
  counters_.add(&LinkCounters::exchanges);
  bool reopened = false;
  if (reconnector_.ask(*transport_, &reopened) != Status::ok) return Status::io_error;
  const FrameCounters before = transport_->counters();
  Status s = drain();
  if (s == Status::ok) {
    outbox_.clear();
    for (auto& d : drives_) d->encode_tick(frame, outbox_);
    s = flush();
  }
  if (s == Status::ok) s = collect();
  const FrameCounters after = transport_->counters();
  counters_.add(&LinkCounters::bytes_received, after.bytes_received - before.bytes_received);
  counters_.add(&LinkCounters::framing_errors, after.malformed - before.malformed);
  if (s != Status::ok) {
    if (s == Status::io_error) reconnector_.lost();
    return s;
  }
  bool incomplete = false;
  for (auto& d : drives_) incomplete |= d->settle() != Status::ok;
  if (incomplete) counters_.add(&LinkCounters::timeouts);
  // Silent or faulted drives are channel faults (telemetry), not a failed link.
  return Status::ok;
}

Status CanLink::release() noexcept {
  outbox_.clear();
  for (auto& d : drives_) d->encode_release(outbox_);
  const Status s = flush();
  if (s == Status::io_error) reconnector_.lost();
  return s;
}

void CanLink::release_channel(std::size_t channel) noexcept {
  for (auto& d : drives_) d->release_channel(channel);
}

std::uint64_t CanLink::saturated_pulses() const noexcept {
  std::uint64_t n = 0;
  for (const auto& d : drives_) n += d->saturated();
  return n;
}

void CanLink::read_telemetry(std::span<ChannelTelemetry> out) const noexcept {
  for (const auto& d : drives_) d->read_telemetry(out);
}

LinkCounters CanLink::counters() const noexcept {
  LinkCounters k = counters_.snapshot();
  k.reconnects = reconnector_.reconnects();
  for (const auto& d : drives_) k.device_errors += d->device_errors();
  return k;
}

}  // namespace avar::firmware_iface
