#pragma once
// HID test helpers: report descriptors of real pads from tests/data/hid (hex text, '#' comments)
// and sinks that record the controls a decoder posts.

#include <cstdint>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "avar/firmware_iface/input_source.hpp"

namespace avar::testing {

/// The bytes of tests/data/hid/<name>: hex pairs separated by blanks, '#' to the end of a line
/// is a comment.
inline std::vector<std::uint8_t> load_hid_fixture(const std::string& name) {
  const std::string path = std::string(AVAR_TEST_DATA_DIR) + "/hid/" + name;
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::vector<std::uint8_t> bytes;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream words(line.substr(0, line.find('#')));
    std::string word;
    while (words >> word) bytes.push_back(static_cast<std::uint8_t>(std::stoul(word, nullptr, 16)));
  }
  return bytes;
}

/// One post() as the sink saw it.
struct PostedControl {
  std::string name;
  double value = 0.0;
  bool bipolar = false;
  std::int64_t arrived_ns = 0;
};

/// Records every post (allocates: not for allocation tests). Thread-safe.
class RecordingControlSink final : public firmware_iface::ControlSink {
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

}  // namespace avar::testing
