#pragma once
// The transport layer of firmware_iface: moves bytes with deadlines and knows nothing of
// servos. Implementations: SerialTransport (libserial), and in tests/sim in-memory ones.

#include <chrono>
#include <cstddef>
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

  /// Moves what has arrived, up to out.size() bytes, into `out` and sets *got to their count,
  /// waiting at most `timeout` for the first byte: for line protocols (SLCAN) whose replies have
  /// no length up front. ok with *got >= 1; timeout with *got == 0 when nothing came; io_error.
  /// Real-time safe. This default reads one byte through read_exact (correct for any transport);
  /// real and simulated ports override it to take everything that is there at once.
  virtual Status read_some(std::span<std::uint8_t> out, std::chrono::milliseconds timeout, std::size_t* got) noexcept {
    *got = 0;
    if (out.empty()) return Status::ok;
    const Status s = read_exact(out.first(1), timeout);
    if (s == Status::ok) *got = 1;
    return s;
  }

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
