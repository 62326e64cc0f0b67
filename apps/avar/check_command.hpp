#pragma once
// `avar check SHOW --rig RIG`: validate both files and report every problem, moving nothing.

#include <iosfwd>
#include <string>

namespace avar::app {

/// How run_check lists a plain show's segments.
enum class SegmentListing {
  infeasible,  ///< each one that asks more than the rig allows (avar check)
  summary,     ///< a count and the worst, then only those over or within 10 % of a limit
  every,       ///< every segment with its share of the limits
};

/// Validates, then lists every segment that asks more speed, acceleration or range of its channel
/// than the rig allows. With retime_path, writes a show stretched just enough to be feasible.
/// Returns kExitOk when the show can play on the rig (the limiter keeps infeasible segments
/// safe), kExitBadInput otherwise.
/// `listing` says how segments are listed (layered shows always list what is infeasible).
int run_check(const std::string& show_path, const std::string& rig_path, const std::string& retime_path, std::ostream& out,
              std::ostream& err, SegmentListing listing = SegmentListing::infeasible);

}  // namespace avar::app
