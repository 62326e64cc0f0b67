#pragma once
// A ControlSink for tests: records every post under a mutex (input sources post from their own
// threads); and a wait for what another thread does.

#include <chrono>
#include <cstdint>
#include <mutex>
#include <thread>
#include <string>
#include <string_view>
#include <vector>

#include "avar/firmware_iface/input_source.hpp"

namespace avar::testing {

struct PostedControl {
  std::string control;
  double value = 0;
  bool bipolar = false;
  std::int64_t arrived_ns = 0;
};

class RecordingControlSink final : public firmware_iface::ControlSink {
 public:
  void post(std::string_view control, double value, bool bipolar, std::int64_t arrived_ns) noexcept override {
    const std::lock_guard lock(mutex_);
    posts_.push_back({std::string(control), value, bipolar, arrived_ns});
  }

  std::vector<PostedControl> posts() const {
    const std::lock_guard lock(mutex_);
    return posts_;
  }

 private:
  mutable std::mutex mutex_;
  std::vector<PostedControl> posts_;
};

/// Polls `predicate` every 2 ms until it holds or `timeout` has passed; whether it held.
template <class Predicate>
bool eventually(Predicate predicate, std::chrono::milliseconds timeout = std::chrono::seconds(5)) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!predicate()) {
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return true;
}

}  // namespace avar::testing
