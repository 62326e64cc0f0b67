#pragma once
// A ByteTransport wired straight to a simulated ByteDevice in the same thread: write() hands the
// bytes to the device, read_exact() takes its replies. The device answers at once, so a reply
// that is not there after the write never comes: read_exact() then reports a timeout without
// waiting. For deterministic driver tests and benchmarks without a pseudo-terminal.
// Not thread-safe (one thread drives both the transport and the device).

#include <array>
#include <string>
#include <vector>

#include "avar/firmware_iface/byte_transport.hpp"
#include "avar/sim/byte_device.hpp"

namespace avar::sim {

class DeviceTransport final : public firmware_iface::ByteTransport {
 public:
  /// The device is borrowed and must outlive the transport.
  explicit DeviceTransport(ByteDevice& device, std::string name = "in-memory") : device_(device), name_(std::move(name)) {}

  /// Not real-time safe (the simulated device allocates).
  Status write(std::span<const std::uint8_t> bytes) noexcept override {
    device_.receive(bytes);
    written_ += bytes.size();
    ++writes_;
    last_write_.assign(bytes.begin(), bytes.end());
    return Status::ok;
  }
  Status read_exact(std::span<std::uint8_t> out, std::chrono::milliseconds) noexcept override {
    return device_.take_replies(out) == out.size() ? Status::ok : Status::timeout;
  }
  void discard_input() noexcept override {
    std::array<std::uint8_t, 256> sink{};
    while (device_.take_replies(sink) > 0) {
    }
  }
  std::uint64_t bytes_written() const noexcept override { return written_; }
  const std::string& name() const noexcept override { return name_; }

  /// write() calls so far, and the bytes of the last one (what a driver sent in one tick).
  std::uint64_t writes() const noexcept { return writes_; }
  const std::vector<std::uint8_t>& last_write() const noexcept { return last_write_; }

 private:
  ByteDevice& device_;
  std::string name_;
  std::uint64_t written_ = 0;
  std::uint64_t writes_ = 0;
  std::vector<std::uint8_t> last_write_;
};

}  // namespace avar::sim
