#pragma once
// `avar check SHOW --rig RIG`: validate both files and report every problem, moving nothing.

#include <iosfwd>
#include <string>

namespace avar::app {

/// Validates, then lists every segment that asks more speed, acceleration or range of its channel
/// than the rig allows. With retime_path, writes a show stretched just enough to be feasible.
/// Returns kExitOk when the show can play on the rig (the limiter keeps infeasible segments
/// safe), kExitBadInput otherwise.
int run_check(const std::string& show_path, const std::string& rig_path, const std::string& retime_path, std::ostream& out,
              std::ostream& err);

}  // namespace avar::app
