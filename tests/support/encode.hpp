#pragma once
// Golden-byte tests of the codecs: run an encoder into a buffer and keep what it wrote.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace avar::testing {

using Bytes = std::vector<std::uint8_t>;

/// Calls f(span) on a buffer of `Capacity` bytes and returns the first f(...) bytes.
template <std::size_t Capacity, class F>
Bytes encode_into(F&& f) {
  std::array<std::uint8_t, Capacity> buf{};
  const std::size_t n = f(std::span<std::uint8_t>(buf));
  return Bytes(buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n));
}

}  // namespace avar::testing
