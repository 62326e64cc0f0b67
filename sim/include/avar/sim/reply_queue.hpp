#pragma once
// The outgoing side of a simulated device: reply bytes waiting for the host to take them.

#include <algorithm>
#include <cstdint>
#include <deque>
#include <span>

namespace avar::sim {

/// Moves up to out.size() bytes from the front of `queue` into `out`; returns how many.
inline std::size_t take_from(std::deque<std::uint8_t>& queue, std::span<std::uint8_t> out) {
  const std::size_t n = std::min(out.size(), queue.size());
  std::copy_n(queue.begin(), n, out.begin());
  queue.erase(queue.begin(), queue.begin() + static_cast<long>(n));
  return n;
}

}  // namespace avar::sim
