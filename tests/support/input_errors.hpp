#pragma once
// Helpers for tests of whole-file validation: edit a good file's text, load it, and compare the
// error after the file name ("":LINE:COLUMN: what was found; what was expected").

#include <gtest/gtest.h>

#include <string>

#include "avar/core/input_error.hpp"
#include "temp_file.hpp"

namespace avar::testing {

/// `text` with its first `from` replaced by `to`; a failing expectation when `from` is missing.
inline std::string replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

/// Writes `text` to a temporary file, calls load(path), and returns the InputError's message
/// after the file name (it must start with it), or "" when the text loaded.
template <class Load>
std::string load_error(Load&& load, const std::string& text, const std::string& name = "under_test.yaml") {
  const std::string path = write_temp_file(name, text);
  try {
    load(path);
    return "";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(path, 0), 0u) << "the message must start with the file name: " << message;
    return message.substr(path.size());
  }
}

}  // namespace avar::testing
