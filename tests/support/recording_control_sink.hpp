#pragma once
// A ControlSink for tests that records every post (input sources post from their own threads),
// and a wait for what another thread does.

#include <chrono>
#include <cstdint>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <string_view>
#include <vector>

#include "avar/inputs/input_source.hpp"

namespace avar::testing {

/// One post() as the sink saw it.
struct PostedControl {
  std::string name;
  double value = 0.0;
  bool bipolar = false;
  std::int64_t arrived_ns = 0;
};

/// Records every post (allocates: not for allocation tests). Thread-safe.
class RecordingControlSink final : public inputs::ControlSink {
 public:
  void post(std::string_view control, double value, bool bipolar, std::int64_t arrived_ns) noexcept override {
    const std::lock_guard lock(mutex_);
    posts_.push_back({std::string(control), value, bipolar, arrived_ns});
    latest_[std::string(control)] = value;
  }
  std::vector<PostedControl> posts() const {
    const std::lock_guard lock(mutex_);
    return posts_;
  }
  /// The latest value of `control`; throws when it was never posted.
  double value(const std::string& control) const {
    const std::lock_guard lock(mutex_);
    const auto it = latest_.find(control);
    if (it == latest_.end()) throw std::out_of_range("control '" + control + "' was never posted");
    return it->second;
  }
  std::size_t size() const {
    const std::lock_guard lock(mutex_);
    return posts_.size();
  }
  void clear() {
    const std::lock_guard lock(mutex_);
    posts_.clear();
  }

 private:
  mutable std::mutex mutex_;
  std::vector<PostedControl> posts_;
  std::map<std::string, double> latest_;
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
