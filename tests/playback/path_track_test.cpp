// Paths: the per-segment cubics reproduce the curve engine's splines, constant-speed traversal is
// measured constant within the arc-length bound, user distance-time curves are honoured, the ends
// hold outside [from, to], Frenet frames stay orthonormal and finite across straight pieces, and
// bad paths are rejected at their location.
#include "avar/playback/path_track.hpp"

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
  for (PathSpline spline : {PathSpline::catmull_rom, PathSpline::bspline, PathSpline::linear}) {
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
  EXPECT_EQ(path_spline_from_name("bezier"), std::nullopt);
}

}  // namespace
}  // namespace avar::playback
