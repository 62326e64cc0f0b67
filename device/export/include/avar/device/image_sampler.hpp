#pragma once
// The device engine's host build sampling a whole show image: what `avar sample --engine device`
// prints and what a test or a simulated device compares with the double engine. Same source, same
// bits as the engine on a microcontroller.

#include <cstdint>
#include <vector>

#include "avar/device/curve_engine.hpp"

namespace avar::device {

class ImageSampler {
 public:
  /// Takes the image and checks it whole; throws std::invalid_argument naming what is wrong.
  explicit ImageSampler(std::vector<std::uint8_t> image);
  ImageSampler(const ImageSampler&) = delete;  // the channels point into the image
  ImageSampler& operator=(const ImageSampler&) = delete;

  std::size_t channel_count() const noexcept { return channels_.size(); }
  std::uint32_t ticks_per_second() const noexcept { return header_.ticks_per_second; }
  std::int32_t duration_ticks() const noexcept { return header_.duration; }
  bool loops() const noexcept { return (header_.flags & kShowLoops) != 0; }

  /// Channel c's 16-bit output at `tick` (the engine's sample()). c < channel_count().
  std::uint16_t output(std::size_t c, std::int32_t tick) noexcept { return sample(channels_[c], caches_[c], tick); }

 private:
  std::vector<std::uint8_t> image_;
  ShowHeader header_{};
  std::vector<Channel> channels_;
  std::vector<SegmentCache> caches_;
};

/// The name of an image status, for messages ("bad magic", ...).
const char* to_string(ImageStatus status);

}  // namespace avar::device
