#pragma once
// Whether a show asks more of a rig than its channels allow, segment by segment, and a retimed
// show that does not. Load-time code: allocates, may throw.

#include <string>
#include <vector>

#include "avar/control/rig.hpp"
#include "avar/core/input_error.hpp"
#include "avar/playback/show.hpp"

namespace avar::config {

struct Infeasible {
  enum class Kind { speed, acceleration, range, jump };
  Kind kind = Kind::speed;
  std::string channel;
  std::string unit;
  double t0 = 0, t1 = 0;   ///< the segment, seconds
  double required = 0;     ///< what the segment asks (units/s, units/s², or the value reached)
  double allowed = 0;      ///< the channel's limit
  SourceLocation where;    ///< the key that starts the segment

  std::string to_string() const;  ///< "file:line:col: jaw 6.8-7 s: speed 150 deg/s, allowed 120 deg/s"
};

/// Every segment of every track that needs more speed or acceleration (measured on the curve
/// between its keys), or more range, than its channel allows, plus step keys that jump (the
/// limiter shapes jumps; they are listed, not retimed). Tracks for unknown channels are skipped
/// (check_show_against_rig reports them).
std::vector<Infeasible> check_feasibility(const playback::Show& show, const control::Rig& rig);

/// A copy of the show whose offending spans are stretched in time just enough for the speed and
/// acceleration limits, every track alike so that they stay in step, all other timing kept
/// (later keys shift by the added time). Jumps and range problems are left as they are.
playback::Show retime(const playback::Show& show, const control::Rig& rig);


}  // namespace avar::config
