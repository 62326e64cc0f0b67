#include "avar/control/frame_mailbox.hpp"

#include <algorithm>

namespace avar::control {

FrameMailbox::FrameMailbox(std::size_t frame_size) {
  for (auto& b : buffers_) b.assign(frame_size, 0.0);
}

void FrameMailbox::publish(std::span<const double> frame) noexcept {
  std::copy(frame.begin(), frame.end(), buffers_[back_].begin());
  // Hand the filled buffer over and take whatever was in the middle (the reader's old one, or
  // an unread frame that is now stale).
  back_ = middle_.exchange(back_ | kFresh, std::memory_order_acq_rel) & ~kFresh;
}

bool FrameMailbox::take(std::span<double> out) noexcept {
  if (!(middle_.load(std::memory_order_acquire) & kFresh)) return false;
  front_ = middle_.exchange(front_, std::memory_order_acq_rel) & ~kFresh;
  const std::vector<double>& newest = buffers_[front_];
  std::copy(newest.begin(), newest.end(), out.begin());
  return true;
}

}  // namespace avar::control
