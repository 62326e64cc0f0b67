#pragma once
// A point moving along a 3-D path (Parent, Computer Animation, 3.2): control points joined by one
// of the curve engine's splines, traversed between two show times at a speed profile given by a
// distance-time function, optionally carrying an orientation along the path.
//
// The path. Each coordinate is a Curve whose keys are the control points at times 0, 1, ..., n-1
// (the common parameter u), all with the chosen interpolation: linear, catmull_rom, cardinal,
// kochanek_bartels or bspline. Every one of these is a cubic polynomial of u on each segment
// [i, i+1], so building recovers each segment's cubic exactly from four samples of the curve
// engine (no spline logic is repeated here) and evaluates position and derivatives from it.
// (The curve engine's Bezier keys are not used: Blender's handle correction makes their segments
// rational in u, not cubic.)
//
// bezier: a 3-D cubic Bezier as Blender's curve objects have it. Segment i is the cubic with
// control points P_i, R_i, L_{i+1}, P_{i+1} (R the right handle, L the left handle), written
// directly in power form. A handle not given is automatic:
// - interior point P with neighbours A (before) and B (after): direction d = the normalised sum of
//   the unit chords (P - A)/|P - A| + (B - P)/|B - P| (Blender's BEZT auto-handle direction; a
//   chord of zero length adds nothing), L = P - d |P - A| / 3, R = P + d |B - P| / 3. Blender
//   scales by 1/2.5614 of the chord instead of 1/3. When d vanishes (the path doubles back) the
//   handle sits on the point.
// - end points: the handle toward the neighbour, R_0 = P_0 + (P_1 - P_0) / 3 and
//   L_n = P_n + (P_{n-1} - P_n) / 3.
// Automatic handles make the tangent direction continuous at every interior point, and dp/du
// divided by the adjacent chord's length is the same from both sides (C1 in the chord-length
// parameter; C1 in u itself only where the two chords are equally long). Since the point is moved
// by distance, its velocity in time is continuous either way. The first point's left handle and
// the last point's right handle are kept (for writing back) but do not shape the path.
//
// Speed. An ArcLengthTable maps travelled distance to u, within kArcLengthTolerance metres, or
// kArcLengthRelativeTolerance of the path's length bound (sum over segments of |c1|+|c2|+|c3|)
// when that is larger: an absolute 0.1 µm over a path kilometres long asks for digits a double
// barely has, and the table would double to its cap at great cost for nothing;
// the distance at show time t is length * s((t - from) / (to - from)), s the distance-time
// function; before `from` and after `to` the point holds the path's ends.
//
// Orientation along the path, as a rotation whose columns are the effector frame's x, y, z axes in
// the base frame:
// - frenet: x the unit tangent T, y the principal normal N, z the binormal T x N. Where the
//   curvature vanishes (straight pieces, inflections) N is carried from the previous sample by
//   parallel transport (the smallest rotation taking the previous tangent to the new one); a path
//   straight from its start takes the first defined normal, or one perpendicular to T if none is.
//   At an inflection of a curved piece the Frenet normal flips sides, as Frenet frames do.
// - tangent: x along the tangent, z the `up` vector made perpendicular to it (y = z x x).
// - look_at: x toward the `look_at` point, z the `up` vector made perpendicular to it.
// Where a frame is undefined (tangent or look direction zero or parallel to up) the previous
// sample's frame is carried. Frames are tabulated at load at kFrameSamples equal steps of
// distance and slerped between, so evaluation is a pure function of time.
//
// Evaluation (position(), sample()) is real-time safe: no allocation, exception or lock, and
// thread-safe (the track is immutable). Building allocates and validates (load time, offline).

#include <array>
#include <cstddef>
#include <optional>
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "avar/core/input_error.hpp"
#include "avar/playback/runtime/arc_length.hpp"
#include "avar/playback/runtime/curve.hpp"
#include "avar/playback/runtime/distance_time.hpp"

namespace avar::playback {

enum class PathSpline : std::uint8_t { linear, catmull_rom, cardinal, kochanek_bartels, bspline, bezier };
/// "linear", "catmull_rom", "cardinal", "kochanek_bartels", "bspline", "bezier"; nullopt otherwise.
std::optional<PathSpline> path_spline_from_name(std::string_view name);
const char* to_string(PathSpline spline);
const char* path_spline_names();  ///< comma separated, for error messages

enum class PathOrientation : std::uint8_t { none, frenet, tangent, look_at };

/// A path as authored: what the show file says, kept for checks and for writing it back.
struct PathSpec {
  std::vector<Eigen::Vector3d> points;  ///< metres, base frame; at least 2
  std::vector<SourceLocation> point_where;
  /// bezier only: each empty (no handles given) or one entry per point, nullopt where the handle
  /// is automatic. Metres, base frame.
  std::vector<std::optional<Eigen::Vector3d>> left, right;
  PathSpline spline = PathSpline::catmull_rom;
  double tension = 0;     ///< cardinal, kochanek_bartels
  double continuity = 0;  ///< kochanek_bartels
  double bias = 0;        ///< kochanek_bartels
  double from = 0;        ///< show seconds when the point leaves points.front()
  double to = 1;          ///< show seconds when it reaches points.back(); > from
  DistanceTime speed{DistanceTimeShape::linear};
  PathOrientation orientation = PathOrientation::none;
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();      ///< tangent, look_at: non-zero
  Eigen::Vector3d look_at = Eigen::Vector3d::Zero();  ///< look_at: the point looked at (base frame)
  SourceLocation where;
};

/// Where the point is at one time, and (when the path orients) how the effector is turned.
struct PathSample {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  ///< identity when the path does not orient
  double distance = 0;                                              ///< metres travelled along the path
};

class PathTrack {
 public:
  static constexpr double kArcLengthTolerance = 1e-7;           ///< metres
  static constexpr double kArcLengthRelativeTolerance = 1e-10;  ///< of the length bound, when larger
  static constexpr std::size_t kFrameSamples = 1024;
  /// Below this curvature (1/m) the Frenet normal is carried instead of computed.
  static constexpr double kMinCurvature = 1e-6;

  /// Validates and builds. Throws InputError (at the spec, or at the offending point) when there
  /// are fewer than 2 points, a coordinate or handle is not finite, handles are given for a spline
  /// that is not bezier or their count differs from the points', to <= from or a time is not
  /// finite, the up vector is zero, or all points are the same point (even when handles would
  /// give the path length). Load time: allocates. Offline: defined by the offline layer
  /// (offline/src/path_build.cpp), like Curve::build.
  explicit PathTrack(PathSpec spec);

  /// The point (and orientation) at show time t (seconds). Real-time safe, thread-safe.
  PathSample sample(double t) const noexcept;
  /// Position at the path parameter u in [0, segments] (clamped). Real-time safe.
  Eigen::Vector3d position_at(double u) const noexcept;
  /// dp/du and d2p/du2 at u (clamped). Real-time safe.
  Eigen::Vector3d derivative_at(double u) const noexcept;
  Eigen::Vector3d second_derivative_at(double u) const noexcept;
  /// The parameter at `distance` metres from the start (clamped to the length). Real-time safe.
  double parameter_at(double distance) const noexcept { return table_.parameter_at(distance); }

  double length() const noexcept { return table_.total_length(); }  ///< metres
  /// The arc-length table's tolerance, metres: how far the distance travelled may be off.
  double length_tolerance() const noexcept { return tolerance_; }
  /// The intervals of the arc-length table (its build cost: the quadratures it made).
  std::size_t length_table_intervals() const noexcept { return table_.intervals(); }
  std::size_t segments() const noexcept { return cubics_.size(); }
  bool orients() const noexcept { return spec_.orientation != PathOrientation::none; }
  const PathSpec& spec() const noexcept { return spec_; }

 private:
  /// p(s) = c[0] + s (c[1] + s (c[2] + s c[3])) on one segment, s = u - i in [0, 1].
  using Cubic = std::array<Eigen::Vector3d, 4>;
  class Parametric;
  static std::vector<Cubic> build_cubics(const PathSpec& spec);
  static std::vector<Cubic> bezier_cubics(const PathSpec& spec);
  static double arc_length_tolerance(const std::vector<Cubic>& cubics) noexcept;
  void build_frames();
  std::size_t locate(double& u) const noexcept;

  PathSpec spec_;
  std::vector<Cubic> cubics_;
  double tolerance_;
  ArcLengthTable table_;
  std::vector<Eigen::Quaterniond> frames_;  ///< at kFrameSamples + 1 equal steps of distance
};

}  // namespace avar::playback
