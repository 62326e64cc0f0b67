#include "avar/device/show_image.hpp"

namespace avar {
namespace device {
namespace {

const int64_t kMaxValue = static_cast<int64_t>(1) << 20;  // output units: 16 ranges either side

bool within(int64_t x, int64_t limit) { return x >= -limit && x <= limit; }

// The features this build plays (config.hpp).
const uint8_t kBuiltFeatures =
    static_cast<uint8_t>((AVAR_DEVICE_EASINGS ? kFeatureEasings : 0) | (AVAR_DEVICE_CYCLES ? kFeatureCycles : 0) |
                         (AVAR_DEVICE_EXTRAPOLATION ? kFeatureExtrapolation : 0));

// Reads one key as the engine does and checks its numbers against the engine's bounds: times
// strictly increasing within 32 bits, values and control points within kMaxValue, parameters
// within their fields' ranges. False when it does not decode or is out of bounds.
// `pending` carries the previous key's second inner control point, relative to this key's value.
// `bezier_seen`: a Bezier key came before (whose handle times a later one may repeat).
bool check_key(ByteReader& r, bool first, int64_t& time, int64_t& value, int64_t& pending, uint8_t& features, bool& bezier_seen) {
  const uint8_t header = r.u8();
  const uint8_t kind = header & 0x1fu;
  if (kind >= kKindCount || ((header >> 5) & 3u) > kEaseInOut) return false;
  if (kind > kBezier) features |= kFeatureEasings;
  if (first) {
    time = r.zigzag();
  } else {
    const uint64_t step = r.varint();
    if (step == 0 || step > 0xffffffffu) return false;
    time += static_cast<int64_t>(step);
  }
  value += r.zigzag();
  if (!within(time, 0x7fffffff) || !within(value, kMaxValue) || !within(value + pending, kMaxValue)) return false;
  pending = 0;
  bool ok = true;
  switch (kind) {
    case kCubic:
    case kBezier: {
      const int64_t inner1 = r.zigzag();
      pending = r.zigzag();
      ok = within(pending, 2 * kMaxValue) && within(inner1, 2 * kMaxValue) && within(value + inner1, kMaxValue);
      if (kind == kBezier) {
        const unsigned bytes = header & kKeyWideBezier ? 3 : 2;
        const uint32_t one = static_cast<uint32_t>(1) << (8 * bytes - 1);  // fractions Q15 or Q23, at most 1
        if (header & 0x40u) return false;                                  // no easing on a Bezier key
        if (header & kKeySameHandleTimes) {
          ok = ok && bezier_seen;
        } else {
          ok = ok && r.fixed(bytes) <= one && r.fixed(bytes) <= one;
        }
        bezier_seen = true;
      }
      break;
    }
    case kBack: ok = within(r.zigzag(), static_cast<int64_t>(1) << 24); break;
    case kElastic: {
      const uint8_t blended = r.u8();
      const int64_t factor_or_amplitude = r.zigzag();
      const uint64_t period = r.varint();
      const int64_t shift = r.zigzag();
      ok = blended <= 1 &&
           (blended ? factor_or_amplitude >= 0 && factor_or_amplitude <= (static_cast<int64_t>(1) << 30)
                    : within(factor_or_amplitude, kMaxValue * 256)) &&
           period > 0 && period <= (static_cast<uint64_t>(1) << 50) && within(shift, static_cast<int64_t>(1) << 49);
      break;
    }
    default: break;
  }
  return ok && !r.overrun;
}

}  // namespace

uint32_t channel_offset(const uint8_t* image, uint8_t channel) {
  ByteReader r = {image, kHeaderSize + 4u * (static_cast<uint32_t>(channel) + 1u), kHeaderSize + 4u * channel, false};
  return r.fixed(4);
}

ImageStatus check_image(const uint8_t* image, uint32_t size, ShowHeader& header) {
  if (size < kHeaderSize) return kImageTooShort;
  ByteReader r = {image, size, 0, false};
  if (r.u8() != 'a' || r.u8() != 'v' || r.u8() != 'd' || r.u8() != '1') return kImageBadMagic;
  if (r.u8() != kFormatVersion) return kImageBadVersion;
  ShowHeader h;
  h.channel_count = r.u8();
  h.flags = r.u8();
  h.snap_ticks = r.u8();
  h.ticks_per_second = r.fixed(4);
  h.duration = static_cast<int32_t>(r.fixed(4));
  h.features = 0;
  if (h.channel_count == 0 || h.channel_count > kMaxChannels) return kImageBadChannelCount;
  if (h.ticks_per_second == 0) return kImageBadTicksPerSecond;
  if (size < kHeaderSize + 4u * h.channel_count) return kImageTooShort;
  for (uint8_t c = 0; c < h.channel_count; ++c) {
    ByteReader k = {image, size, channel_offset(image, c), false};
    if (k.at >= size) return kImageBadChannel;
    const uint8_t flags = k.u8();
    const uint32_t keys = k.fixed(2);
    if (keys == 0 || (flags & ~(kChannelLinearExtrapolation | kChannelCycles)) != 0) return kImageBadChannel;
    if (flags & kChannelLinearExtrapolation) h.features |= kFeatureExtrapolation;
    if (flags & kChannelCycles) h.features |= kFeatureCycles;
    if (flags & kChannelLinearExtrapolation) {
      if (!within(k.zigzag(), static_cast<int64_t>(1) << 40) || !within(k.zigzag(), static_cast<int64_t>(1) << 40))
        return kImageBadChannel;
    }
    if (flags & kChannelCycles) {
      const uint8_t modes = k.u8();
      if ((modes & 0x0fu) > kCycleMirror || (modes >> 4) > kCycleMirror) return kImageBadChannel;
      if (k.varint() > 0x7fffffffu || k.varint() > 0x7fffffffu || !within(k.zigzag(), kMaxValue * 512)) return kImageBadChannel;
    }
    int64_t time = 0, value = 0, pending = 0;
    bool bezier_seen = false;
    for (uint32_t i = 0; i < keys; ++i)
      if (!check_key(k, i == 0, time, value, pending, h.features, bezier_seen)) return kImageBadChannel;
    if (pending != 0) return kImageBadChannel;  // the last key starts no segment
  }
  header = h;
  return (h.features & ~kBuiltFeatures) != 0 ? kImageNeedsFeature : kImageOk;
}

}  // namespace device
}  // namespace avar
