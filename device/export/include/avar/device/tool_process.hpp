#pragma once
// Running a build tool or an emulator from avar export --verify: a program found on PATH, its
// standard output and error together, its exit status, a time limit. Load-time code (blocks).

#include <optional>
#include <string>
#include <vector>

namespace avar::device {

struct ToolRun {
  int status = -1;  ///< the exit status; -1 when it did not start, was killed or timed out
  bool timed_out = false;
  std::string output;  ///< standard output and standard error, interleaved as written
  double seconds = 0;  ///< wall time
};

/// The full path of `program` found on PATH, or nothing.
std::optional<std::string> find_program(const std::string& program);

/// Runs argv[0] (found on PATH) with standard input closed; kills it after `timeout_s`.
ToolRun run_tool(const std::vector<std::string>& argv, double timeout_s);

}  // namespace avar::device
