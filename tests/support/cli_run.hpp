#pragma once
// Running the `avar` command line in-process in tests: arguments in, exit code and both output
// streams out.

#include <sstream>
#include <string>
#include <vector>

#include "avar/cli.hpp"

namespace avar::testing {

struct CliResult {
  int code;
  std::string out;
  std::string err;
};

/// run_cli with argv = {"avar", args...}.
inline CliResult run_avar(std::vector<std::string> args) {
  args.insert(args.begin(), "avar");
  std::vector<const char*> argv;
  for (const auto& a : args) argv.push_back(a.c_str());
  std::ostringstream out, err;
  const int code = app::run_cli(static_cast<int>(argv.size()), argv.data(), out, err);
  return {code, out.str(), err.str()};
}

}  // namespace avar::testing
