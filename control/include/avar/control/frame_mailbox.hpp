#pragma once
// A latest-value mailbox for frames of doubles between one writer and one reader thread (a
// triple buffer): the writer never waits and never overwrites the frame being read; the reader
// always gets the newest complete frame, and older ones are dropped. Both sides are wait-free
// and allocation-free after construction.

#include <array>
#include <atomic>
#include <cstdint>
#include <span>
#include <vector>

namespace avar::control {

class FrameMailbox {
 public:
  explicit FrameMailbox(std::size_t frame_size);

  /// Writer thread: makes `frame` the newest. Real-time safe.
  void publish(std::span<const double> frame) noexcept;

  /// Reader thread: copies the newest frame into `out` if one arrived since the last take;
  /// returns false (and leaves `out` alone) otherwise. Real-time safe.
  bool take(std::span<double> out) noexcept;

 private:
  static constexpr std::uint32_t kFresh = 4;  // flag beside the buffer index (0..2)
  std::array<std::vector<double>, 3> buffers_;
  std::atomic<std::uint32_t> middle_{0};  ///< index of the buffer in the middle, | kFresh when unread
  std::uint32_t back_ = 1;               ///< writer's buffer (writer thread only)
  std::uint32_t front_ = 2;              ///< reader's buffer (reader thread only)
};

}  // namespace avar::control
