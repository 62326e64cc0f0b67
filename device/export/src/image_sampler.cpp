#include "avar/device/image_sampler.hpp"

#include <stdexcept>
#include <string>
#include <utility>

namespace avar::device {

const char* to_string(ImageStatus status) {
  switch (status) {
    case kImageOk: return "ok";
    case kImageTooShort: return "shorter than its header and channel table";
    case kImageBadMagic: return "not a device show image (expected \"avd1\")";
    case kImageBadVersion: return "an image of another format version";
    case kImageBadChannelCount: return "a channel count outside 1..64";
    case kImageBadTicksPerSecond: return "0 ticks per second";
    case kImageBadChannel: return "a channel record or key that does not decode within the engine's bounds";
    case kImageNeedsFeature: return "a segment family or channel feature this build of the engine left out";
  }
  return "an unknown image status";
}

ImageSampler::ImageSampler(std::vector<std::uint8_t> image) : image_(std::move(image)) {
  const auto size = static_cast<std::uint32_t>(image_.size());
  const ImageStatus status = check_image(image_.data(), size, header_);
  if (status != kImageOk) throw std::invalid_argument(std::string("the device show image has ") + to_string(status));
  channels_.resize(header_.channel_count);
  caches_.resize(header_.channel_count);
  for (std::uint8_t c = 0; c < header_.channel_count; ++c) {
    if (!open_channel(image_.data(), size, c, channels_[c]))
      throw std::invalid_argument("the device show image's channel " + std::to_string(c) + " does not open");
    reset_cache(caches_[c]);
  }
}

}  // namespace avar::device
