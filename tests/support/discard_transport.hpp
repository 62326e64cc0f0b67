#pragma once
// A byte transport that counts what it is given and throws it away, so that a test or a
// benchmark measures avar's own work, not a link's. Reads time out at once; the clock stands at 0.
// write() and bytes_written() may run on different threads (a link's I/O thread, the test's).

#include <atomic>
#include <chrono>
#include <cstdint>
#include <span>
#include <string>

#include "avar/firmware_iface/byte_transport.hpp"

namespace avar::testing {

class DiscardTransport final : public firmware_iface::ByteTransport {
 public:
  Status write(std::span<const std::uint8_t> bytes) noexcept override {
    written_.fetch_add(bytes.size(), std::memory_order_relaxed);
    return Status::ok;
  }
  Status read_exact(std::span<std::uint8_t>, std::chrono::milliseconds) noexcept override { return Status::timeout; }
  std::chrono::nanoseconds now() const noexcept override { return {}; }
  void discard_input() noexcept override {}
  Status reopen() noexcept override { return Status::ok; }
  std::uint64_t bytes_written() const noexcept override { return written_.load(std::memory_order_relaxed); }
  const std::string& name() const noexcept override { return name_; }

 private:
  std::atomic<std::uint64_t> written_{0};
  std::string name_ = "discard";
};

}  // namespace avar::testing
