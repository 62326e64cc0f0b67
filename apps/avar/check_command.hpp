#pragma once
// `avar check SHOW --rig RIG`: validate both files and report every problem, moving nothing.

#include <iosfwd>
#include <string>

namespace avar::app {

/// Returns kExitOk when the show can play on the rig, kExitBadInput otherwise.
int run_check(const std::string& show_path, const std::string& rig_path, std::ostream& out, std::ostream& err);

}  // namespace avar::app
