#pragma once
// A ByteTransport wired straight to a simulated device, on a simulated clock, in the caller's
// thread: no pseudo-terminal, no scheduler, fully deterministic. Every byte costs its time on
// the wire at the configured baud rate (10 bit times per byte, 8N1) and the device moves by that
// time, so a driver's achievable tick rate on a real bus can be measured byte for byte. A read
// that the device does not answer in full costs its whole timeout. The wire can be unplugged
// and plugged back in (reopen() fails while unplugged). For tests and benchmarks.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "avar/firmware_iface/byte_transport.hpp"
#include "avar/firmware_iface/wire_time.hpp"
#include "avar/sim/byte_device.hpp"

namespace avar::sim {

class SimWire final : public firmware_iface::ByteTransport {
 public:
  /// device is borrowed and must outlive this. turnaround_s: time between the end of a request
  /// and the first reply byte (the device's return delay), charged once per read that waits.
  SimWire(ByteDevice& device, int baud = 1'000'000, double turnaround_s = 0, std::string name = "simulated wire");

  Status write(std::span<const std::uint8_t> bytes) noexcept override;
  Status read_exact(std::span<std::uint8_t> out, std::chrono::milliseconds timeout) noexcept override;
  /// Takes what the device has sent; when it has sent nothing, waits the turnaround, then the
  /// whole timeout (as read_exact does). The bytes taken cost their wire time.
  Status read_some(std::span<std::uint8_t> out, std::chrono::milliseconds timeout, std::size_t* got) noexcept override;
  /// The simulated clock (now_s()).
  std::chrono::nanoseconds now() const noexcept override {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::duration<double>(now_s_));
  }
  void discard_input() noexcept override;
  Status reopen() noexcept override;
  std::uint64_t bytes_written() const noexcept override { return bytes_written_; }
  const std::string& name() const noexcept override { return name_; }

  /// Unplugs (false) or plugs back (true) the wire. While unplugged, writes and reads fail with
  /// io_error and reopen() fails; once plugged back, reopen() succeeds.
  void set_connected(bool connected) noexcept { connected_ = connected; }
  /// Simulated seconds since construction: the wire time of every byte plus waits.
  double now_s() const noexcept { return now_s_; }
  std::uint64_t bytes_read() const noexcept { return bytes_read_; }
  std::uint64_t reopens() const noexcept { return reopens_; }
  /// Writes that reached the device, and the bytes of the last one (for tests of what a driver
  /// sends per tick).
  std::uint64_t writes() const noexcept { return writes_; }
  const std::vector<std::uint8_t>& last_write() const noexcept { return last_write_; }

 private:
  /// Lets simulated time pass for the device.
  void pass(double dt_s) noexcept;
  /// Moves the device's replies into pending_.
  void collect() noexcept;

  ByteDevice& device_;
  int baud_;
  double turnaround_s_;
  std::string name_;
  bool connected_ = true;
  bool open_ = true;
  double now_s_ = 0;
  std::uint64_t bytes_written_ = 0;
  std::uint64_t bytes_read_ = 0;
  std::uint64_t reopens_ = 0;
  std::uint64_t writes_ = 0;
  std::vector<std::uint8_t> last_write_;  ///< capacity reserved: no allocation per write
  std::array<std::uint8_t, 8192> pending_{};  ///< received, not yet read
  std::size_t pending_size_ = 0;
};

}  // namespace avar::sim
