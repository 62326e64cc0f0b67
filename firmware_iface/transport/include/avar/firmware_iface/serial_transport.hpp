#pragma once
// ByteTransport over a serial port (USB CDC such as /dev/ttyACM0, a UART, or the slave side of a
// pseudo-terminal), using libserial. 8N1, no flow control, raw bytes.

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "avar/firmware_iface/byte_transport.hpp"

namespace LibSerial {
class SerialPort;
}

namespace avar::firmware_iface {

class SerialTransport final : public ByteTransport {
 public:
  /// Opens and configures the port, and takes an exclusive lock on it so that two programs
  /// never drive one device. Throws InputError naming the port when it is missing, not a
  /// serial device, busy, or the baud rate is not one the port supports. Not real-time.
  SerialTransport(const std::string& path, int baud);
  ~SerialTransport() override;
  SerialTransport(const SerialTransport&) = delete;
  SerialTransport& operator=(const SerialTransport&) = delete;

  Status write(std::span<const std::uint8_t> bytes) noexcept override;
  Status read_exact(std::span<std::uint8_t> out, std::chrono::milliseconds timeout) noexcept override;
  /// Waits on the port's descriptor (poll) and reads what is there, straight into `out`.
  Status read_some(std::span<std::uint8_t> out, std::chrono::milliseconds timeout, std::size_t* got) noexcept override;
  /// The monotonic clock (steady_clock): a port lives in real time.
  std::chrono::nanoseconds now() const noexcept override;
  void discard_input() noexcept override;
  /// Opens the same path again (a udev symlink such as /dev/serial/by-id/... follows the device
  /// to its new node), with the same settings and lock.
  Status reopen() noexcept override;
  /// Readable from any thread.
  std::uint64_t bytes_written() const noexcept override { return bytes_written_.load(std::memory_order_relaxed); }
  const std::string& name() const noexcept override { return path_; }

  /// Baud rates a serial port can be opened at (the termios standard set).
  static bool is_supported_baud(int baud) noexcept;

  /// Largest single write or read; longer requests fail with out_of_range.
  static constexpr std::size_t max_chunk = 4096;

 private:
  /// Opens, locks and configures port_; throws InputError naming the path.
  void open_port();
  void close_port() noexcept;

  std::string path_;
  int baud_ = 0;
  std::unique_ptr<LibSerial::SerialPort> port_;
  std::vector<std::uint8_t> write_buffer_;  // capacity max_chunk, reused: no allocation per write
  std::vector<std::uint8_t> read_buffer_;   // capacity max_chunk, reused
  std::atomic<std::uint64_t> bytes_written_{0};
};

}  // namespace avar::firmware_iface
