#pragma once
// The transport layer of firmware_iface: moves bytes with deadlines and knows nothing of
// servos. Implementations: SerialTransport (libserial), and in tests/sim in-memory ones.

#include <chrono>
#include <cstdint>
#include <span>
#include <string>

#include "avar/core/status.hpp"

namespace avar::firmware_iface {

class ByteTransport {
 public:
  virtual ~ByteTransport() = default;

  /// Sends all of `bytes`. Real-time safe in implementations: no allocation, no exception.
  virtual Status write(std::span<const std::uint8_t> bytes) noexcept = 0;

  /// Fills `out` completely, waiting at most `timeout` in total. Returns timeout when fewer
  /// bytes arrived (what did arrive is discarded). Real-time safe: no allocation, no exception.
  virtual Status read_exact(std::span<std::uint8_t> out, std::chrono::milliseconds timeout) noexcept = 0;

  /// Now on the transport's own clock, for reply deadlines: the monotonic clock for a real port,
  /// simulated time for a simulated wire (a transport without time may return a constant, and
  /// read timeouts alone then bound a wait). Drivers take every deadline from here and read no
  /// clock themselves. Real-time safe.
  virtual std::chrono::nanoseconds now() const noexcept = 0;

  /// Drops whatever has been received and not yet read (stale replies).
  virtual void discard_input() noexcept = 0;

  /// Closes and opens the transport again after an I/O error (a USB adapter unplugged and
  /// plugged back in, a device that reset). Returns ok once it is usable again, io_error while
  /// it is still gone. Not real-time: opening allocates and waits; call it from a link's I/O
  /// thread, never from the tick.
  virtual Status reopen() noexcept = 0;

  /// Total bytes written since the transport was opened.
  virtual std::uint64_t bytes_written() const noexcept = 0;

  /// A human-readable name for messages, such as the port path.
  virtual const std::string& name() const noexcept = 0;
};

}  // namespace avar::firmware_iface
