#pragma once
// A latest-value mailbox for frames (arrays of T: channel values, device telemetry) between one
// writer and one reader thread (a triple buffer): the writer never waits and never overwrites
// the frame being read; the reader always gets the newest complete frame, and older ones are
// dropped. Both sides are wait-free and allocation-free after construction. T must be trivially
// copyable.

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

namespace avar::control {

template <class T>
class LatestFrameMailbox {
  static_assert(std::is_trivially_copyable_v<T>);

 public:
  explicit LatestFrameMailbox(std::size_t frame_size, const T& initial = T{}) {
    for (auto& b : buffers_) b.assign(frame_size, initial);
  }

  /// Writer thread: makes `frame` the newest. Real-time safe.
  void publish(std::span<const T> frame) noexcept {
    std::copy(frame.begin(), frame.end(), buffers_[back_].begin());
    // Hand the filled buffer over and take whatever was in the middle (the reader's old one, or
    // an unread frame that is now stale).
    back_ = middle_.exchange(back_ | kFresh, std::memory_order_acq_rel) & ~kFresh;
  }

  /// Reader thread: copies the newest frame into `out` if one arrived since the last take;
  /// returns false (and leaves `out` alone) otherwise. Real-time safe.
  bool take(std::span<T> out) noexcept {
    if (!(middle_.load(std::memory_order_acquire) & kFresh)) return false;
    front_ = middle_.exchange(front_, std::memory_order_acq_rel) & ~kFresh;
    const std::vector<T>& newest = buffers_[front_];
    std::copy(newest.begin(), newest.end(), out.begin());
    return true;
  }

 private:
  static constexpr std::uint32_t kFresh = 4;  // flag beside the buffer index (0..2)
  std::array<std::vector<T>, 3> buffers_;
  std::atomic<std::uint32_t> middle_{0};  ///< index of the buffer in the middle, | kFresh when unread
  std::uint32_t back_ = 1;               ///< writer's buffer (writer thread only)
  std::uint32_t front_ = 2;              ///< reader's buffer (reader thread only)
};

/// Frames of channel values.
using FrameMailbox = LatestFrameMailbox<double>;

}  // namespace avar::control
