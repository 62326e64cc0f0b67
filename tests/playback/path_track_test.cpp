// Paths: the per-segment cubics reproduce the curve engine's splines, constant-speed traversal is
// measured constant within the arc-length bound, user distance-time curves are honoured, the ends
// hold outside [from, to], Frenet frames stay orthonormal and finite across straight pieces, and
// bad paths are rejected at their location.
#include "avar/playback/runtime/path_track.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "keys.hpp"

namespace avar::playback {
namespace {

using testing::key;
using testing::raw_curve;

PathSpec spec_of(std::vector<Eigen::Vector3d> points, PathSpline spline = PathSpline::catmull_rom) {
  PathSpec spec;
  spec.points = std::move(points);
  spec.spline = spline;
  spec.from = 1;
  spec.to = 4;
  spec.where = {"path.yaml", 7, 5};
  return spec;
}

/// A figure eight in the y-z plane, a metre across.
std::vector<Eigen::Vector3d> figure_eight() {
  std::vector<Eigen::Vector3d> p;
  for (int i = 0; i <= 12; ++i) {
    const double a = 2 * M_PI * i / 12;
    p.emplace_back(0.3, 0.5 * std::sin(a), 0.25 * std::sin(2 * a));
  }
  return p;
}

/// The path seen through its public evaluation, to measure lengths independently of its table.
struct Measured : ParametricCurve {
  explicit Measured(const PathTrack& p) : path(p) {}
  const PathTrack& path;
  double u_begin() const noexcept override { return 0; }
  double u_end() const noexcept override { return static_cast<double>(path.segments()); }
  Eigen::Vector3d position(double u) const noexcept override { return path.position_at(u); }
  Eigen::Vector3d derivative(double u) const noexcept override { return path.derivative_at(u); }
};

TEST(PathTrack, SegmentCubicsReproduceEverySplineOfTheCurveEngine) {
  const std::vector<Eigen::Vector3d> points = {{0, 0, 0}, {0.3, 0.1, -0.2}, {0.5, 0.6, 0.1}, {0.2, 0.9, 0.4}, {-0.1, 0.5, 0.3}};
  const std::pair<PathSpline, Interpolation> splines[] = {
      {PathSpline::linear, Interpolation::linear},
      {PathSpline::catmull_rom, Interpolation::catmull_rom}, {PathSpline::cardinal, Interpolation::cardinal},
      {PathSpline::kochanek_bartels, Interpolation::kochanek_bartels}, {PathSpline::bspline, Interpolation::bspline}};
  for (const auto& [spline, interpolation] : splines) {
    PathSpec spec = spec_of(points, spline);
    spec.tension = 0.3;
    spec.continuity = -0.2;
    spec.bias = 0.4;
    const PathTrack path(spec);
    EXPECT_EQ(path_spline_from_name(to_string(spline)), spline);
    for (Eigen::Index axis = 0; axis < 3; ++axis) {
      std::vector<RawKey> keys;
      for (std::size_t i = 0; i < points.size(); ++i) {
        RawKey k = key(static_cast<double>(i), points[i][axis], interpolation);
        k.tension = 0.3;
        k.continuity = -0.2;
        k.bias = 0.4;
        keys.push_back(k);
      }
      const Curve curve = Curve::build(raw_curve(keys));
      for (double u = 0; u <= 4; u += 0.01)
        ASSERT_NEAR(path.position_at(u)[axis], curve.evaluate(u), 1e-9) << to_string(spline) << " axis " << axis << " u " << u;
    }
  }
}

TEST(PathTrack, LinearSpeedCoversEqualDistancesInEqualTimesWithinTheArcLengthBound) {
  for (PathSpline spline : {PathSpline::catmull_rom, PathSpline::bspline, PathSpline::linear, PathSpline::bezier}) {
    const PathTrack path(spec_of(figure_eight(), spline));
    const Measured measured(path);
    constexpr int kSteps = 300;
    const double step = path.length() / kSteps;
    double u_previous = path.parameter_at(path.sample(1.0).distance);
    EXPECT_EQ(u_previous, 0.0);
    for (int i = 1; i <= kSteps; ++i) {
      const PathSample s = path.sample(1.0 + 3.0 * i / kSteps);
      const double u = path.parameter_at(s.distance);
      // The table's inverse is within the bound at both ends of the step.
      ASSERT_NEAR(arc_length(measured, u_previous, u, 1e-11), step, 2 * PathTrack::kArcLengthTolerance)
          << to_string(spline) << " step " << i;
      ASSERT_TRUE(s.position.isApprox(path.position_at(u), 1e-14));
      u_previous = u;
    }
    EXPECT_NEAR(arc_length(measured, 0, static_cast<double>(path.segments()), 1e-11), path.length(), PathTrack::kArcLengthTolerance);
  }
}

TEST(PathTrack, AFarPointLoosensTheLengthToleranceToItsScaleAndKeepsTheTableSmall) {
  // Found by the show-file fuzzer: a typo (-0825 for -0.25) put one point 825 m out, and the
  // absolute 0.1 µm bound drove the table to its cap (seconds of load in the sanitizer build).
  std::vector<Eigen::Vector3d> points = figure_eight();
  const PathTrack small(spec_of(points));
  EXPECT_EQ(small.length_tolerance(), PathTrack::kArcLengthTolerance);
  points[5].y() = -825;
  const PathTrack far(spec_of(points));
  EXPECT_GT(far.length(), 1650.0);
  EXPECT_GT(far.length_tolerance(), PathTrack::kArcLengthTolerance);
  EXPECT_LE(far.length_tolerance(), 1e-9 * far.length());
  EXPECT_LE(far.length_table_intervals(), 1024u);
  // The table still meets its bound: equal distances at equal times, measured independently.
  const Measured measured(far);
  constexpr int kSteps = 200;
  double u_previous = 0;
  for (int i = 1; i <= kSteps; ++i) {
    const double u = far.parameter_at(far.length() * i / kSteps);
    ASSERT_NEAR(arc_length(measured, u_previous, u, 1e-3 * far.length_tolerance()), far.length() / kSteps,
                2 * far.length_tolerance())
        << "step " << i;
    u_previous = u;
  }
}

TEST(PathTrack, HoldsItsEndsBeforeFromAndAfterTo) {
  const PathTrack path(spec_of(figure_eight()));
  for (double t : {-5.0, 0.0, 1.0, std::nan("")}) EXPECT_TRUE(path.sample(t).position.isApprox(path.position_at(0), 1e-15)) << t;
  const Eigen::Vector3d end = path.position_at(static_cast<double>(path.segments()));
  for (double t : {4.0, 4.5, 1e9}) EXPECT_TRUE(path.sample(t).position.isApprox(end, 1e-12)) << t;
  EXPECT_TRUE(path.position_at(0).isApprox(figure_eight().front(), 1e-12));  // catmull_rom interpolates its points
  EXPECT_TRUE(end.isApprox(figure_eight().back(), 1e-12));
}

TEST(PathTrack, DistanceFollowsTheChosenDistanceTimeFunctionIncludingAUserCurve) {
  PathSpec spec = spec_of(figure_eight());
  spec.speed = DistanceTime::from_keys(raw_curve({key(0, 0, Interpolation::bezier), key(0.5, 0.2, Interpolation::linear), key(1, 1)}));
  const PathTrack path(spec);
  for (double t = 0; t <= 1; t += 0.01) {
    const double expected = path.length() * spec.speed.distance(t);
    EXPECT_NEAR(path.sample(1 + 3 * t).distance, expected, 1e-12) << t;
  }
  EXPECT_NEAR(path.sample(1 + 1.5).distance, 0.2 * path.length(), 1e-12);
  spec.speed = DistanceTime(DistanceTimeShape::sine_constant_middle, 0.2, 0.8);
  const PathTrack eased(spec);
  EXPECT_NEAR(eased.sample(2.5).distance, 0.5 * eased.length(), 1e-9);
  EXPECT_LT(eased.sample(1.1).distance, 0.05 * eased.length() * 1.0);
}

void expect_frame(const Eigen::Quaterniond& q, const std::string& what) {
  ASSERT_TRUE(q.coeffs().allFinite()) << what;
  ASSERT_NEAR(q.norm(), 1, 1e-12) << what;
  const Eigen::Matrix3d m = q.toRotationMatrix();
  ASSERT_TRUE((m.transpose() * m).isApprox(Eigen::Matrix3d::Identity(), 1e-12)) << what;
  ASSERT_NEAR(m.determinant(), 1, 1e-12) << what;
}

TEST(PathTrack, FrenetFramesStayOrthonormalFiniteAndAlongTheTangentAcrossStraightPieces) {
  // A straight run along x, a bend, another straight run along y, then a bend out of the plane.
  const std::vector<Eigen::Vector3d> points = {{0, 0, 0}, {0.1, 0, 0}, {0.2, 0, 0}, {0.3, 0, 0}, {0.4, 0.1, 0},
                                               {0.4, 0.2, 0}, {0.4, 0.3, 0}, {0.4, 0.4, 0}, {0.3, 0.5, 0.1}};
  for (PathSpline spline : {PathSpline::catmull_rom, PathSpline::linear, PathSpline::bspline}) {
    PathSpec spec = spec_of(points, spline);
    spec.orientation = PathOrientation::frenet;
    const PathTrack path(spec);
    for (double t = 1; t <= 4; t += 0.001) {
      const PathSample s = path.sample(t);
      const std::string what = std::string(to_string(spline)) + " at " + std::to_string(t);
      expect_frame(s.orientation, what);
      const Eigen::Vector3d tangent = path.derivative_at(path.parameter_at(s.distance));
      if (tangent.norm() > 1e-6 && spline != PathSpline::linear) {  // a polyline turns at its corners between frame samples
        // Within the frame table's spacing of the true tangent.
        ASSERT_GT((s.orientation * Eigen::Vector3d::UnitX()).dot(tangent.normalized()), std::cos(0.2)) << what;
      }
    }
  }
  // A path straight from end to end has a frame everywhere.
  PathSpec straight = spec_of({{0, 0, 0}, {0.5, 0.5, 0.5}, {1, 1, 1}}, PathSpline::catmull_rom);
  straight.orientation = PathOrientation::frenet;
  const PathTrack line(straight);
  for (double t = 0; t <= 5; t += 0.01) {
    const Eigen::Quaterniond q = line.sample(t).orientation;
    expect_frame(q, "straight at " + std::to_string(t));
    ASSERT_NEAR((q * Eigen::Vector3d::UnitX()).dot(Eigen::Vector3d(1, 1, 1).normalized()), 1, 1e-9);
  }
}

TEST(PathTrack, FrenetNormalPointsToTheCentreOfACircle) {
  std::vector<Eigen::Vector3d> circle;
  for (int i = 0; i <= 16; ++i) circle.emplace_back(std::cos(M_PI * i / 16), std::sin(M_PI * i / 16), 0);
  PathSpec spec = spec_of(circle);
  spec.orientation = PathOrientation::frenet;
  const PathTrack path(spec);
  const PathSample s = path.sample(2.5);
  const Eigen::Vector3d inward = -s.position.normalized();
  EXPECT_GT((s.orientation * Eigen::Vector3d::UnitY()).dot(inward), 0.99);
  EXPECT_GT((s.orientation * Eigen::Vector3d::UnitZ()).dot(Eigen::Vector3d::UnitZ()), 0.99);  // counter-clockwise: binormal up
}

TEST(PathTrack, TangentAndLookAtFramesKeepZUp) {
  PathSpec spec = spec_of(figure_eight());
  spec.orientation = PathOrientation::look_at;
  spec.look_at = {1, 0, 0};
  const PathTrack look(spec);
  spec.orientation = PathOrientation::tangent;
  spec.up = {0, 0, 2};
  const PathTrack along(spec);
  for (double t = 1; t <= 4; t += 0.01) {
    const PathSample s = look.sample(t);
    expect_frame(s.orientation, "look_at");
    const Eigen::Vector3d toward = (spec.look_at - s.position).normalized();
    ASSERT_GT((s.orientation * Eigen::Vector3d::UnitX()).dot(toward), std::cos(0.02)) << t;
    ASSERT_GE((s.orientation * Eigen::Vector3d::UnitZ()).z(), 0) << t;
    const PathSample a = along.sample(t);
    expect_frame(a.orientation, "tangent");
    const Eigen::Vector3d forward = a.orientation * Eigen::Vector3d::UnitX();
    ASSERT_NEAR(forward.dot((a.orientation * Eigen::Vector3d::UnitY())), 0, 1e-12);
    ASSERT_NEAR((a.orientation * Eigen::Vector3d::UnitY()).z(), 0, 1e-2) << t;  // y stays horizontal
  }
}

TEST(PathTrack, BadPathsAreRejectedAtTheirLocation) {
  const auto message = [](PathSpec spec) {
    try {
      PathTrack path(std::move(spec));
      return std::string();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
  };
  EXPECT_EQ(message(spec_of({{0, 0, 0}})), "path.yaml:7:5: a path needs at least 2 points; found 1");
  PathSpec backwards = spec_of(figure_eight());
  backwards.to = 1;
  EXPECT_EQ(message(backwards), "path.yaml:7:5: expected a path's end time `to` (1 s) after its start time `from` (1 s)");
  EXPECT_NE(message(spec_of({{1, 1, 1}, {1, 1, 1}})).find("all the same point"), std::string::npos);
  PathSpec no_up = spec_of(figure_eight());
  no_up.up = Eigen::Vector3d::Zero();
  EXPECT_NE(message(no_up).find("up vector"), std::string::npos);
  EXPECT_EQ(path_spline_from_name("hermite"), std::nullopt);
  EXPECT_EQ(path_spline_from_name("bezier"), PathSpline::bezier);
  PathSpec bad_handle = spec_of({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}, PathSpline::bezier);
  bad_handle.point_where = {{"path.yaml", 8, 7}, {"path.yaml", 9, 7}, {"path.yaml", 10, 7}};
  bad_handle.right = {std::nullopt, Eigen::Vector3d(1, NAN, 0), std::nullopt};
  EXPECT_EQ(message(bad_handle), "path.yaml:9:7: expected a path handle of finite numbers within ±1e6 m");
  // Huge but finite: the differences would overflow (and the arc length with them).
  PathSpec huge = bad_handle;
  huge.right = {};
  huge.points[1] = Eigen::Vector3d(1, -1e308, 0);
  EXPECT_EQ(message(huge), "path.yaml:9:7: expected a path point of finite numbers within ±1e6 m");
  PathSpec not_bezier = bad_handle;
  not_bezier.spline = PathSpline::catmull_rom;
  not_bezier.right = {std::nullopt, Eigen::Vector3d(1, 1, 0), std::nullopt};
  EXPECT_EQ(message(not_bezier), "path.yaml:7:5: handles do not belong to a catmull_rom path; expected them only on bezier paths");
  PathSpec short_handles = bad_handle;
  short_handles.left = {std::nullopt};
  EXPECT_EQ(message(short_handles), "path.yaml:7:5: expected one handle entry per path point (3), found 1");
}

/// dp/du at the end of the segment before point i (u -> i from below).
Eigen::Vector3d derivative_before(const PathTrack& path, std::size_t i) {
  return path.derivative_at(std::nextafter(static_cast<double>(i), 0.0));
}

TEST(PathTrack, BezierPassesThroughItsPointsAndLeavesThemAlongTheirHandles) {
  const std::vector<Eigen::Vector3d> points = {{0, 0, 0}, {0.4, 0.1, 0.2}, {0.6, 0.5, 0.1}, {0.3, 0.8, 0.4}};
  PathSpec spec = spec_of(points, PathSpline::bezier);
  const Eigen::Vector3d along(0.2, 0.1, -0.3);  // aligned handles at point 1: left behind, right ahead
  spec.left = {Eigen::Vector3d(-5, -5, -5), points[1] - 0.5 * along, std::nullopt, Eigen::Vector3d(0.3, 0.7, 0.5)};
  spec.right = {Eigen::Vector3d(0.1, -0.1, 0), points[1] + 1.5 * along, Eigen::Vector3d(0.7, 0.6, 0.3), std::nullopt};
  const PathTrack path(spec);
  ASSERT_EQ(path.segments(), 3u);
  for (std::size_t i = 0; i < points.size(); ++i)
    EXPECT_TRUE(path.position_at(static_cast<double>(i)).isApprox(points[i], 1e-14)) << "point " << i;
  // The Bezier derivative at an end is three times the vector to the handle, on both sides.
  EXPECT_TRUE(path.derivative_at(0).isApprox(3 * (*spec.right[0] - points[0]), 1e-14));
  EXPECT_TRUE(path.derivative_at(1).isApprox(3 * 1.5 * along, 1e-14));
  EXPECT_TRUE(derivative_before(path, 1).isApprox(3 * 0.5 * along, 1e-9));
  const Eigen::Vector3d across = (*spec.right[1] - *spec.left[1]).normalized();
  EXPECT_NEAR(path.derivative_at(1).normalized().dot(across), 1, 1e-14);
  EXPECT_NEAR(derivative_before(path, 1).normalized().dot(across), 1, 1e-9);
  EXPECT_TRUE(derivative_before(path, 3).isApprox(3 * (points[3] - *spec.left[3]), 1e-9));
  // Golden midpoint of segment 1: (P1 + 3 R1 + 3 L2 + P2) / 8, L2 automatic.
  const Eigen::Vector3d a = (points[2] - points[1]).normalized(), b = (points[3] - points[2]).normalized();
  const Eigen::Vector3d left2 = points[2] - (a + b).normalized() * (points[2] - points[1]).norm() / 3;
  EXPECT_TRUE(path.position_at(1.5).isApprox((points[1] + 3 * *spec.right[1] + 3 * left2 + points[2]) / 8, 1e-14));
  // The first left and last right handles do not shape the path.
  PathSpec unused = spec;
  unused.left[0] = Eigen::Vector3d(9, 9, 9);
  unused.right[3] = Eigen::Vector3d(-9, 9, 9);
  const PathTrack same(unused);
  for (double u = 0; u <= 3; u += 0.05) ASSERT_EQ(same.position_at(u), path.position_at(u)) << u;
}

TEST(PathTrack, BezierAutoHandlesAreC1InChordLengthAtInteriorPointsAndAimAtTheNeighbourAtTheEnds) {
  const unsigned seed = 20261201;
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> coordinate(-1, 1);
  // Few families: each builds a whole path (arc-length table, frames), slow in sanitizer builds.
  for (int family = 0; family < 4; ++family) {
    std::vector<Eigen::Vector3d> points(3 + family);
    for (Eigen::Vector3d& p : points) p = {coordinate(random), coordinate(random), coordinate(random)};
    const PathTrack path(spec_of(points, PathSpline::bezier));
    const std::size_t last = points.size() - 1;
    ASSERT_TRUE(path.derivative_at(0).isApprox(points[1] - points[0], 1e-12)) << "seed " << seed;
    ASSERT_TRUE(derivative_before(path, last).isApprox(points[last] - points[last - 1], 1e-9)) << "seed " << seed;
    for (std::size_t i = 1; i < last; ++i) {
      const double chord_before = (points[i] - points[i - 1]).norm(), chord_after = (points[i + 1] - points[i]).norm();
      const Eigen::Vector3d before = derivative_before(path, i) / chord_before, after = path.derivative_at(static_cast<double>(i)) / chord_after;
      ASSERT_LT((before - after).norm(), 1e-9) << "seed " << seed << " family " << family << " point " << i;
      const Eigen::Vector3d direction = ((points[i] - points[i - 1]) / chord_before + (points[i + 1] - points[i]) / chord_after).normalized();
      ASSERT_TRUE(after.isApprox(direction, 1e-12)) << "seed " << seed << " point " << i;  // unit: |dp/du| is the chord
      ASSERT_TRUE(path.position_at(static_cast<double>(i)).isApprox(points[i], 1e-12)) << "seed " << seed;
    }
  }
}

}  // namespace
}  // namespace avar::playback
