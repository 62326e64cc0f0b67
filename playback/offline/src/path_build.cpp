// PathTrack's construction: validation, the segments' cubics (from the curve builder's splines or
// from Bezier handles), the arc-length table and the tabulated frames (the offline half of
// path_track.hpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include <Eigen/LU>

#include "avar/core/format.hpp"
#include "avar/playback/runtime/path_track.hpp"

namespace avar::playback {
namespace {

Interpolation interpolation_of(PathSpline spline) {
  switch (spline) {
    case PathSpline::linear: return Interpolation::linear;
    case PathSpline::catmull_rom: return Interpolation::catmull_rom;
    case PathSpline::cardinal: return Interpolation::cardinal;
    case PathSpline::kochanek_bartels: return Interpolation::kochanek_bartels;
    case PathSpline::bspline: return Interpolation::bspline;
    case PathSpline::bezier: break;  // built from its handles, not from the curve engine
  }
  return Interpolation::linear;
}

/// The coordinate `axis` of every control point as a curve of the parameter u = point index.
Curve coordinate_curve(const PathSpec& spec, Eigen::Index axis) {
  RawCurve raw({}, spec.where);
  for (std::size_t i = 0; i < spec.points.size(); ++i) {
    RawKey key;
    key.time = static_cast<double>(i);
    key.value = spec.points[i][axis];
    key.interpolation = interpolation_of(spec.spline);
    key.tension = spec.tension;
    key.continuity = spec.continuity;
    key.bias = spec.bias;
    key.where = spec.point_where.size() == spec.points.size() ? spec.point_where[i] : spec.where;
    raw.keys.push_back(key);
  }
  return Curve::build(raw);
}

/// A unit vector perpendicular to the unit vector v.
Eigen::Vector3d any_perpendicular(const Eigen::Vector3d& v) {
  Eigen::Index least = 0;
  v.cwiseAbs().minCoeff(&least);
  return v.cross(Eigen::Vector3d::Unit(least)).normalized();
}

/// The rotation whose columns are x, z x x, z for orthonormal x, z.
Eigen::Quaterniond frame_from(const Eigen::Vector3d& x, const Eigen::Vector3d& z) {
  Eigen::Matrix3d m;
  m.col(0) = x;
  m.col(1) = z.cross(x);
  m.col(2) = z;
  return Eigen::Quaterniond(m).normalized();
}

/// `direction` unit, and `up` made perpendicular to it, when both are defined.
bool up_frame(const Eigen::Vector3d& direction, const Eigen::Vector3d& up, Eigen::Quaterniond& out) {
  const double n = direction.norm();
  if (!(n > 1e-12)) return false;
  const Eigen::Vector3d x = direction / n;
  const Eigen::Vector3d z = up - up.dot(x) * x;
  if (!(z.norm() > 1e-9 * up.norm())) return false;
  out = frame_from(x, z.normalized());
  return true;
}

}  // namespace

/// The path as the arc-length machinery sees it.
class PathTrack::Parametric final : public ParametricCurve {
 public:
  explicit Parametric(const PathTrack& path) : path_(path) {}
  double u_begin() const noexcept override { return 0; }
  double u_end() const noexcept override { return static_cast<double>(path_.segments()); }
  Eigen::Vector3d position(double u) const noexcept override { return path_.position_at(u); }
  Eigen::Vector3d derivative(double u) const noexcept override { return path_.derivative_at(u); }

 private:
  const PathTrack& path_;
};

std::vector<PathTrack::Cubic> PathTrack::build_cubics(const PathSpec& spec) {
  if (spec.points.size() < 2)
    throw InputError(spec.where, "a path needs at least 2 points; found " + std::to_string(spec.points.size()));
  // Huge coordinates are refused with the non-finite ones: their differences overflow, and the
  // path's length with them.
  constexpr double kMaxCoordinate = 1e6;  // metres
  const auto bounded = [&](const Eigen::Vector3d& v) { return v.allFinite() && v.cwiseAbs().maxCoeff() <= kMaxCoordinate; };
  for (std::size_t i = 0; i < spec.points.size(); ++i)
    if (!bounded(spec.points[i]))
      throw InputError(i < spec.point_where.size() ? spec.point_where[i] : spec.where,
                       "expected a path point of finite numbers within ±1e6 m");
  if (!std::isfinite(spec.from) || !std::isfinite(spec.to) || !(spec.to > spec.from))
    throw InputError(spec.where, "expected a path's end time `to` (" + format_number(spec.to) +
                                     " s) after its start time `from` (" + format_number(spec.from) + " s)");
  if (!spec.up.allFinite() || !(spec.up.norm() > 0)) throw InputError(spec.where, "expected a non-zero finite up vector");
  if (!spec.look_at.allFinite()) throw InputError(spec.where, "expected a finite look_at point");
  if (std::all_of(spec.points.begin(), spec.points.end(), [&](const Eigen::Vector3d& p) { return p == spec.points.front(); }))
    throw InputError(spec.where, "a path's points are all the same point; expected a path of non-zero length");
  const auto where_of = [&](std::size_t i) { return i < spec.point_where.size() ? spec.point_where[i] : spec.where; };
  for (const auto* handles : {&spec.left, &spec.right}) {
    if (handles->empty()) continue;
    if (spec.spline != PathSpline::bezier)
      throw InputError(spec.where, std::string("handles do not belong to a ") + to_string(spec.spline) +
                                       " path; expected them only on bezier paths");
    if (handles->size() != spec.points.size())
      throw InputError(spec.where, "expected one handle entry per path point (" + std::to_string(spec.points.size()) +
                                       "), found " + std::to_string(handles->size()));
    for (std::size_t i = 0; i < handles->size(); ++i)
      if ((*handles)[i] && !bounded(*(*handles)[i]))
        throw InputError(where_of(i), "expected a path handle of finite numbers within ±1e6 m");
  }
  if (spec.spline == PathSpline::bezier) return bezier_cubics(spec);

  const std::array<Curve, 3> coordinates = {coordinate_curve(spec, 0), coordinate_curve(spec, 1), coordinate_curve(spec, 2)};
  // Every supported spline is a cubic of u on each segment: four interior samples determine it.
  constexpr std::array<double, 4> kS = {0.125, 0.375, 0.625, 0.875};
  Eigen::Matrix4d vandermonde;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) vandermonde(r, c) = std::pow(kS[static_cast<std::size_t>(r)], c);
  const Eigen::Matrix4d inverse = vandermonde.inverse();
  std::vector<Cubic> cubics(spec.points.size() - 1);
  for (std::size_t i = 0; i < cubics.size(); ++i) {
    for (Eigen::Index axis = 0; axis < 3; ++axis) {
      Eigen::Vector4d samples;
      for (int r = 0; r < 4; ++r)
        samples[r] =
            coordinates[static_cast<std::size_t>(axis)].evaluate(static_cast<double>(i) + kS[static_cast<std::size_t>(r)]);
      const Eigen::Vector4d c = inverse * samples;
      for (std::size_t k = 0; k < 4; ++k) cubics[i][k][axis] = c[static_cast<Eigen::Index>(k)];
    }
  }
  return cubics;
}

std::vector<PathTrack::Cubic> PathTrack::bezier_cubics(const PathSpec& spec) {
  const std::vector<Eigen::Vector3d>& p = spec.points;
  const std::size_t n = p.size();
  const auto given = [](const std::vector<std::optional<Eigen::Vector3d>>& handles, std::size_t i) {
    return handles.empty() ? std::nullopt : handles[i];
  };
  const auto unit_chord = [&](std::size_t from) -> Eigen::Vector3d {
    const Eigen::Vector3d chord = p[from + 1] - p[from];
    const double length = chord.norm();
    return length > 0 ? Eigen::Vector3d(chord / length) : Eigen::Vector3d::Zero();
  };
  const auto auto_direction = [&](std::size_t i) -> Eigen::Vector3d {
    const Eigen::Vector3d sum = unit_chord(i - 1) + unit_chord(i);
    const double length = sum.norm();
    return length > 1e-12 ? Eigen::Vector3d(sum / length) : Eigen::Vector3d::Zero();
  };
  const auto right_of = [&](std::size_t i) -> Eigen::Vector3d {
    if (const auto h = given(spec.right, i)) return *h;
    if (i == 0) return p[0] + (p[1] - p[0]) / 3;
    return p[i] + auto_direction(i) * (p[i + 1] - p[i]).norm() / 3;
  };
  const auto left_of = [&](std::size_t i) -> Eigen::Vector3d {
    if (const auto h = given(spec.left, i)) return *h;
    if (i == n - 1) return p[i] + (p[i - 1] - p[i]) / 3;
    return p[i] - auto_direction(i) * (p[i] - p[i - 1]).norm() / 3;
  };
  std::vector<Cubic> cubics(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const Eigen::Vector3d a = p[i], b = right_of(i), c = left_of(i + 1), d = p[i + 1];
    // Bernstein to power form: (1-s)^3 a + 3 s (1-s)^2 b + 3 s^2 (1-s) c + s^3 d.
    cubics[i] = {a, 3 * (b - a), 3 * (a - 2 * b + c), d - a + 3 * (b - c)};
  }
  return cubics;
}

double PathTrack::arc_length_tolerance(const std::vector<Cubic>& cubics) noexcept {
  // |p'(s)| = |c1 + 2 s c2 + 3 s^2 c3| integrates over [0, 1] to at most |c1| + |c2| + |c3|.
  double bound = 0;
  for (const Cubic& c : cubics) bound += c[1].norm() + c[2].norm() + c[3].norm();
  return std::max(kArcLengthTolerance, kArcLengthRelativeTolerance * bound);
}

PathTrack::PathTrack(PathSpec spec)
    : spec_(std::move(spec)),
      cubics_(build_cubics(spec_)),
      tolerance_(arc_length_tolerance(cubics_)),
      table_(Parametric(*this), tolerance_) {
  build_frames();
}

void PathTrack::build_frames() {
  if (spec_.orientation == PathOrientation::none) return;
  const std::size_t n = kFrameSamples + 1;
  std::vector<double> us(n);
  std::vector<Eigen::Vector3d> tangents(n);
  std::vector<bool> defined(n);
  for (std::size_t k = 0; k < n; ++k) {
    us[k] = table_.parameter_at(length() * static_cast<double>(k) / kFrameSamples);
    const Eigen::Vector3d d = derivative_at(us[k]);
    defined[k] = d.norm() > 1e-12;
    tangents[k] = defined[k] ? Eigen::Vector3d(d.normalized()) : Eigen::Vector3d::Zero();
  }
  // Carry tangents over points where the speed vanishes (backwards for the start).
  const auto first = std::find(defined.begin(), defined.end(), true);
  const Eigen::Vector3d first_tangent =
      first == defined.end() ? Eigen::Vector3d::UnitX() : tangents[static_cast<std::size_t>(first - defined.begin())];
  for (std::size_t k = 0; k < n; ++k)
    if (!defined[k]) tangents[k] = k == 0 ? first_tangent : tangents[k - 1];

  frames_.resize(n);
  if (spec_.orientation == PathOrientation::frenet) {
    std::vector<Eigen::Vector3d> normals(n, Eigen::Vector3d::Zero());
    std::vector<bool> curved(n, false);
    for (std::size_t k = 0; k < n; ++k) {
      const Eigen::Vector3d d = derivative_at(us[k]);
      const double speed2 = d.squaredNorm();
      if (!(speed2 > 1e-24)) continue;
      const Eigen::Vector3d a = second_derivative_at(us[k]);
      const Eigen::Vector3d bend = (a - a.dot(tangents[k]) * tangents[k]) / speed2;  // curvature vector (1/m)
      if (bend.norm() > kMinCurvature) {
        normals[k] = bend.normalized();
        curved[k] = true;
      }
    }
    const auto bent = std::find(curved.begin(), curved.end(), true);
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    if (bent != curved.end()) {
      const Eigen::Vector3d seed = normals[static_cast<std::size_t>(bent - curved.begin())];
      normal = seed - seed.dot(tangents[0]) * tangents[0];
    }
    normal = normal.norm() > 1e-6 ? Eigen::Vector3d(normal.normalized()) : any_perpendicular(tangents[0]);
    for (std::size_t k = 0; k < n; ++k) {
      if (curved[k]) {
        normal = normals[k];
      } else if (k > 0) {  // parallel transport: the smallest rotation from the previous tangent
        normal = Eigen::Quaterniond::FromTwoVectors(tangents[k - 1], tangents[k]) * normal;
        normal -= normal.dot(tangents[k]) * tangents[k];
        normal = normal.norm() > 1e-9 ? Eigen::Vector3d(normal.normalized()) : any_perpendicular(tangents[k]);
      }
      frames_[k] = frame_from(tangents[k], tangents[k].cross(normal));
    }
    return;
  }
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector3d direction =
        spec_.orientation == PathOrientation::tangent ? tangents[k] : Eigen::Vector3d(spec_.look_at - position_at(us[k]));
    if (up_frame(direction, spec_.up, frames_[k])) continue;
    if (k > 0) frames_[k] = frames_[k - 1];
    else if (!up_frame(tangents[0], spec_.up, frames_[0])) frames_[0] = frame_from(tangents[0], any_perpendicular(tangents[0]));
  }
}

}  // namespace avar::playback
