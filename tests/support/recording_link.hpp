#pragma once
// An actuator link for controller tests: records every frame and channel release it is sent, and
// can be told to fail from a given send on.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "avar/firmware_iface/actuator_link.hpp"

namespace avar::testing {

class RecordingLink final : public firmware_iface::ActuatorLink {
 public:
  Status start() override { return Status::ok; }
  Status read_positions(std::span<double>, std::span<bool>) override { return Status::ok; }
  Status send(std::span<const double> frame) noexcept override {
    if (fail_from_send >= 0 && static_cast<int>(frames.size()) >= fail_from_send) return Status::io_error;
    frames.emplace_back(frame.begin(), frame.end());
    return Status::ok;
  }
  Status release() noexcept override {
    ++releases;
    return Status::ok;
  }
  void release_channel(std::size_t channel) noexcept override { released_channels.push_back(channel); }
  std::uint64_t saturated_pulses() const noexcept override { return 0; }
  const std::string& describe() const noexcept override { return name; }

  std::vector<std::vector<double>> frames;
  std::vector<std::size_t> released_channels;
  int fail_from_send = -1;  ///< the send (counted from 0) from which on every send fails; -1: never
  int releases = 0;
  std::string name = "recording link";
};

}  // namespace avar::testing
