#pragma once
// A ByteTransport whose device answers with the fuzzer's bytes: reads take the next bytes of the
// script (timeout once it runs out), writes go nowhere. For fuzzing a link's reply handling.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <string>

#include "avar/firmware_iface/actuator_link.hpp"
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

/// Reads the positions of `link`'s first three channels until the script runs out; a flag byte
/// before each read picks `other_query` (the link's own query: errors, moving) instead. Aborts on
/// a position the link says it knows that is not finite.
template <class Query>
void read_link_until_script_ends(firmware_iface::ActuatorLink& link, ByteReader& in, Query other_query) {
  std::array<double, 3> frame{};
  while (!in.empty()) {
    if (in.flag()) {
      other_query();
      continue;
    }
    bool known[3] = {false, false, false};
    if (link.read_positions(frame, known) != Status::ok) continue;
    for (std::size_t i = 0; i < frame.size(); ++i)
      if (known[i] && !std::isfinite(frame[i])) std::abort();
  }
}

}  // namespace avar::fuzz
