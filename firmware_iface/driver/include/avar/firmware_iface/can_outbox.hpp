#pragma once
// A bounded list of frames to send in one go, sized once at start: drives append their frames for
// a tick without allocating. Real-time safe after construction.

#include <cstddef>
#include <span>
#include <vector>

#include "avar/firmware_iface/can_frame.hpp"

namespace avar::firmware_iface {

class CanOutbox {
 public:
  explicit CanOutbox(std::size_t capacity) { frames_.reserve(capacity); }

  /// Appends a frame; false (and nothing appended) when the outbox is full.
  bool push(const CanFrame& frame) noexcept {
    if (frames_.size() == frames_.capacity()) return false;
    frames_.push_back(frame);
    return true;
  }
  std::span<const CanFrame> frames() const noexcept { return frames_; }
  std::size_t size() const noexcept { return frames_.size(); }
  void clear() noexcept { frames_.clear(); }

 private:
  std::vector<CanFrame> frames_;
};

}  // namespace avar::firmware_iface
