#pragma once
// A ByteTransport whose device answers with the fuzzer's bytes: reads take the next bytes of the
// script (timeout once it runs out), writes go nowhere. For fuzzing a link's reply handling.

#include <algorithm>
#include <string>

#include "avar/firmware_iface/byte_transport.hpp"
#include "fuzz_bytes.hpp"

namespace avar::fuzz {

class ScriptedTransport final : public firmware_iface::ByteTransport {
 public:
  explicit ScriptedTransport(ByteReader& script) : script_(script) {}

  Status write(std::span<const std::uint8_t> bytes) noexcept override {
    written_ += bytes.size();
    return Status::ok;
  }
  Status read_exact(std::span<std::uint8_t> out, std::chrono::milliseconds) noexcept override {
    const auto got = script_.take(out.size());
    std::copy(got.begin(), got.end(), out.begin());
    return got.size() == out.size() ? Status::ok : Status::timeout;
  }
  Status read_some(std::span<std::uint8_t> out, std::chrono::milliseconds, std::size_t* got) noexcept override {
    const auto bytes = script_.take(std::min<std::size_t>(out.size(), script_.u8() % 32 + 1));
    std::copy(bytes.begin(), bytes.end(), out.begin());
    *got = bytes.size();
    return bytes.empty() ? Status::timeout : Status::ok;
  }
  std::chrono::nanoseconds now() const noexcept override { return now_ += std::chrono::milliseconds(1); }
  void discard_input() noexcept override {}
  Status reopen() noexcept override { return Status::ok; }
  std::uint64_t bytes_written() const noexcept override { return written_; }
  const std::string& name() const noexcept override { return name_; }

 private:
  ByteReader& script_;
  std::uint64_t written_ = 0;
  mutable std::chrono::nanoseconds now_{0};
  std::string name_ = "fuzz script";
};

}  // namespace avar::fuzz
