#include "avar/control/threaded_link.hpp"

namespace avar::control {

ThreadedLink::ThreadedLink(firmware_iface::ActuatorLink& inner, std::size_t frame_size, std::uint32_t watchdog_ticks)
    : inner_(inner),
      mailbox_(frame_size),
      io_frame_(frame_size, 0.0),
      telemetry_mailbox_(frame_size),
      io_telemetry_(frame_size),
      telemetry_(frame_size),
      watchdog_ticks_(watchdog_ticks) {
  thread_ = std::thread([this] { serve(); });
}

ThreadedLink::~ThreadedLink() {
  stop_.store(true, std::memory_order_release);
  wake_.store(true, std::memory_order_release);
  wake_.notify_one();
  thread_.join();
}

Status ThreadedLink::start() { return inner_.start(); }

Status ThreadedLink::read_positions(std::span<double> frame, std::span<bool> known) {
  return inner_.read_positions(frame, known);
}

Status ThreadedLink::send(std::span<const double> frame) noexcept {
  mailbox_.publish(frame);
  wake_.store(true, std::memory_order_release);
  wake_.notify_one();
  const std::uint64_t done = completions_.load(std::memory_order_acquire);
  if (done != last_seen_completions_) {
    last_seen_completions_ = done;
    ticks_without_completion_ = 0;
  } else if (++ticks_without_completion_ > watchdog_ticks_) {
    return Status::timeout;
  }
  return last_status_.load(std::memory_order_acquire);
}

Status ThreadedLink::release() noexcept {
  release_requested_.store(true, std::memory_order_release);
  wake_.store(true, std::memory_order_release);
  wake_.notify_one();
  return Status::ok;
}

void ThreadedLink::read_telemetry(std::span<firmware_iface::ChannelTelemetry> out) const noexcept {
  telemetry_mailbox_.take(telemetry_);
  // Only the channels this link has heard about: the others belong to other links.
  for (std::size_t c = 0; c < telemetry_.size() && c < out.size(); ++c)
    if (telemetry_[c].updates > 0) out[c] = telemetry_[c];
}

void ThreadedLink::serve() {
  bool released = false;
  for (;;) {
    wake_.wait(false, std::memory_order_acquire);
    wake_.store(false, std::memory_order_release);
    if (release_requested_.load(std::memory_order_acquire) && !released) {
      last_status_.store(inner_.release(), std::memory_order_release);
      released = true;
    }
    if (stop_.load(std::memory_order_acquire)) return;
    if (released || !mailbox_.take(io_frame_)) continue;
    last_status_.store(inner_.send(io_frame_), std::memory_order_release);
    inner_.read_telemetry(io_telemetry_);
    telemetry_mailbox_.publish(io_telemetry_);
    completions_.fetch_add(1, std::memory_order_acq_rel);
  }
}

}  // namespace avar::control
