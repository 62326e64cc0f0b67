#pragma once
// The avar command line: parses argv with CLI11 and runs one subcommand.

#include <iosfwd>

namespace avar::app {

/// Returns the process exit code. Output goes to out/err (not to std::cout directly) so tests
/// can run commands in-process.
int run_cli(int argc, const char* const* argv, std::ostream& out, std::ostream& err);

}  // namespace avar::app
