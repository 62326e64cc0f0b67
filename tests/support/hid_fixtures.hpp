#pragma once
// HID test helpers: report descriptors of real pads from tests/data/hid (hex text, '#' comments)
// (the sink that records what a decoder posts: recording_control_sink.hpp).

#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "recording_control_sink.hpp"

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

}  // namespace avar::testing
