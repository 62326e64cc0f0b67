#include "avar/firmware_iface/can_frame.hpp"

#include <algorithm>

namespace avar::firmware_iface {

bool CanFrame::operator==(const CanFrame& o) const noexcept {
  if (id != o.id || extended != o.extended || rtr != o.rtr || error != o.error || dlc != o.dlc) return false;
  const auto a = payload();
  const auto b = o.payload();
  return std::equal(a.begin(), a.end(), b.begin(), b.end());
}

CanFrame can_data_frame(std::uint32_t id, std::span<const std::uint8_t> bytes, bool extended) noexcept {
  CanFrame f;
  f.id = id;
  f.extended = extended;
  f.dlc = static_cast<std::uint8_t>(std::min(bytes.size(), kCanMaxData));
  std::copy_n(bytes.begin(), f.dlc, f.data.begin());
  return f;
}

CanFrame can_remote_frame(std::uint32_t id, std::uint8_t dlc, bool extended) noexcept {
  CanFrame f;
  f.id = id;
  f.extended = extended;
  f.rtr = true;
  f.dlc = dlc;
  return f;
}

bool can_frame_valid(const CanFrame& f) noexcept {
  if (f.error) return true;
  return f.dlc <= kCanMaxData && f.id <= (f.extended ? kCanMaxExtendedId : kCanMaxStandardId);
}

bool is_standard_can_bitrate(int bitrate) noexcept {
  for (int b : {10'000, 20'000, 50'000, 100'000, 125'000, 250'000, 500'000, 800'000, 1'000'000})
    if (bitrate == b) return true;
  return false;
}

}  // namespace avar::firmware_iface
