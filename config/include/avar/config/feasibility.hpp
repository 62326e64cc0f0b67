#pragma once
// Whether a show asks more of a rig than its channels allow, segment by segment, and a retimed
// show that does not. Load-time code: allocates, may throw.

#include <string>
#include <vector>

#include "avar/rig/rig.hpp"
#include "avar/core/input_error.hpp"
#include "avar/playback/runtime/show.hpp"

namespace avar::config {

struct Infeasible {
  enum class Kind { speed, acceleration, range, jump };
  Kind kind = Kind::speed;
  std::string channel;
  std::string unit;
  double t0 = 0, t1 = 0;  ///< the segment, seconds
  double required = 0;    ///< what the segment asks (units/s, units/s², or the value reached)
  double allowed = 0;     ///< the channel's limit
  SourceLocation where;   ///< the key that starts the segment

  std::string to_string() const;  ///< "file:line:col: jaw 6.8-7 s: speed 150 deg/s, allowed 120 deg/s"
};

/// What one played segment of a plain show's track asks of its channel, against its limits.
struct SegmentDemand {
  std::string channel;
  std::string unit;
  double t0 = 0, t1 = 0;                          ///< the played part of the segment, seconds
  double speed = 0, acceleration = 0;             ///< largest, units/s and units/s²
  double low = 0, high = 0;                       ///< extremes reached, channel units
  double max_velocity = 0, max_acceleration = 0;  ///< the channel's limits
  double min = 0, max = 0;
  SourceLocation where;  ///< the key that starts the segment

  /// The largest share of a limit the segment uses: speed / max_velocity, acceleration /
  /// max_acceleration, and, for a segment leaving the range, 1 + how far outside over the range.
  /// Above 1 the segment asks more than the channel allows.
  double usage() const;
  /// "file:line:col: jaw 0.7-0.72 s: speed 91 % of 300 deg/s, acceleration 40 % of 8000 deg/s²"
  std::string to_string() const;
};

/// Every played segment of every analog track of a plain show, measured as check_feasibility
/// measures it (step segments, digital channels and channels the rig lacks are left out). A
/// layered show has no segments of its own: empty.
std::vector<SegmentDemand> segment_demands(const playback::Show& show, const rig::Rig& rig);

/// Every segment of every track that needs more speed or acceleration (measured on the curve
/// between its keys), or more range, than its channel allows, plus step keys that jump (the
/// limiter shapes jumps; they are listed, not retimed). Tracks for unknown channels are skipped
/// (check_show_against_rig reports them), and so are digital channels (they switch at once).
///
/// A layered show is checked on its composed motion, channel by channel, as the sampler plays it
/// on this rig (rest pose under channels without a show track): the show is cut at every time
/// where the composition may turn a corner or jump (key times of the show's tracks, placement
/// starts, ends and fade edges, and the show times at which each placement meets one of its
/// clip's key times through its time warp and mode); each piece is measured as a segment is, and
/// a discontinuity at a cut (a placement without a fade, a step key) is listed as a jump.
/// Consecutive pieces with the same finding for the same placement are merged into one span.
/// If any channel is unknown to the rig nothing is checked (check_show_against_rig reports it).
std::vector<Infeasible> check_feasibility(const playback::Show& show, const rig::Rig& rig);

/// A copy of the show whose offending spans are stretched in time just enough for the speed and
/// acceleration limits, every track alike so that they stay in step, all other timing kept
/// (later keys and cues shift by the added time). Jumps and range problems are left as they are. Throws
/// InputError for a layered show: stretching show time would move where its clips overlap and
/// fade, so it is refused rather than retimed dishonestly.
playback::Show retime(const playback::Show& show, const rig::Rig& rig);

}  // namespace avar::config
