#pragma once
// The seam between a simulated device and whatever carries its bytes (a pseudo-terminal host,
// an in-memory transport). A device decodes exactly what the real one accepts and answers as
// the real one does. Not thread-safe: its host serialises every call.

#include <cstddef>
#include <cstdint>
#include <span>

namespace avar::sim {

class ByteDevice {
 public:
  virtual ~ByteDevice() = default;
  /// Bytes arriving from the host's side of the wire, in order.
  virtual void receive(std::span<const std::uint8_t> bytes) = 0;
  /// Moves up to out.size() pending reply bytes into `out`, oldest first; returns how many.
  virtual std::size_t take_replies(std::span<std::uint8_t> out) = 0;
  /// Advances the device's simulated time by dt_s seconds (servo motion, timers).
  virtual void advance(double dt_s) = 0;
  /// Total bytes received so far.
  virtual std::uint64_t bytes_received() const = 0;
};

}  // namespace avar::sim
