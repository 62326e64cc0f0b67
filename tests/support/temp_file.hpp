#pragma once
// Temporary files for tests. ctest runs tests in parallel processes, so every path carries the
// running test's name and the process id: no two tests ever share a file. Whatever was made at
// these paths (files or folders, by the test or by a program it ran) is removed when the test
// passes; a failed test's files stay for inspection.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <vector>

namespace avar::testing {

namespace detail {

/// The paths handed out during the running test.
inline std::vector<std::string>& handed_out_paths() {
  static std::vector<std::string> paths;
  return paths;
}

class TempFileCleaner final : public ::testing::EmptyTestEventListener {
  void OnTestEnd(const ::testing::TestInfo& info) override {
    if (!info.result()->Failed())
      for (const std::string& path : handed_out_paths()) {
        std::error_code ignored;
        std::filesystem::remove_all(path, ignored);
      }
    handed_out_paths().clear();
  }
};

/// Registers the cleaner once per test program (gtest owns and deletes it).
inline const bool cleaner_registered = [] {
  ::testing::UnitTest::GetInstance()->listeners().Append(new TempFileCleaner);
  return true;
}();

}  // namespace detail

/// A path in the temporary folder, unique to the running test.
inline std::string temp_path(const std::string& name) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string path = ::testing::TempDir() + "avar-" + info->test_suite_name() + "-" + info->name() + "-" +
                     std::to_string(::getpid()) + "-" + name;
  detail::handed_out_paths().push_back(path);
  return path;
}

/// Writes `text` to temp_path(name) and returns the path.
inline std::string write_temp_file(const std::string& name, const std::string& text) {
  const std::string path = temp_path(name);
  std::ofstream(path) << text;
  return path;
}

}  // namespace avar::testing
