#pragma once
// Little-endian fields of the device's formats (show image, figure record), as the exporters
// write them.

#include <cstdint>
#include <vector>

namespace avar::device {

/// The low `bytes` bytes of v, least significant first.
inline void put_fixed(std::vector<std::uint8_t>& out, std::uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}

}  // namespace avar::device
