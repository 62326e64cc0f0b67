#pragma once
// Time a number of bytes takes on an asynchronous serial line, for link budgets and simulated
// device timing. Pure, constexpr, real-time safe.

#include <cstddef>

namespace avar::firmware_iface {

/// Bit times per byte: 8N1 = start + 8 data + 1 stop = 10; 8N2 (DMX512) = 11.
inline constexpr double kBitsPerByte8N1 = 10;
inline constexpr double kBitsPerByte8N2 = 11;

/// Seconds `bytes` bytes occupy the line at `baud` bits per second (no gaps between bytes).
/// baud > 0.
constexpr double wire_seconds(std::size_t bytes, double baud, double bits_per_byte = kBitsPerByte8N1) noexcept {
  return static_cast<double>(bytes) * bits_per_byte / baud;
}

}  // namespace avar::firmware_iface
