#pragma once
// Temporary files for tests. ctest runs tests in parallel processes, so every path carries the
// running test's name and the process id: no two tests ever share a file.

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <string>

namespace avar::testing {

/// A path in the temporary folder, unique to the running test.
inline std::string temp_path(const std::string& name) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  return ::testing::TempDir() + "avar-" + info->test_suite_name() + "-" + info->name() + "-" + std::to_string(::getpid()) +
         "-" + name;
}

/// Writes `text` to temp_path(name) and returns the path.
inline std::string write_temp_file(const std::string& name, const std::string& text) {
  const std::string path = temp_path(name);
  std::ofstream(path) << text;
  return path;
}

}  // namespace avar::testing
