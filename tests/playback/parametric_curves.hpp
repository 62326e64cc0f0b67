#pragma once
// Parametric curves with known arc lengths, for the arc-length and speed-control tests.

#include <Eigen/Core>
#include <cmath>
#include <random>

#include "avar/playback/runtime/arc_length.hpp"

namespace avar::playback::testing {

/// Helix (r cos u, r sin u, pitch u) over [0, turns]; pitch 0 is a circle arc. Length
/// sqrt(r^2 + pitch^2) * (u1 - u0).
struct Helix : ParametricCurve {
  double r = 1, pitch = 0, u0 = 0, u1 = 1;
  Helix(double r_in, double pitch_in, double u0_in, double u1_in) : r(r_in), pitch(pitch_in), u0(u0_in), u1(u1_in) {}
  double u_begin() const noexcept override { return u0; }
  double u_end() const noexcept override { return u1; }
  Eigen::Vector3d position(double u) const noexcept override { return {r * std::cos(u), r * std::sin(u), pitch * u}; }
  Eigen::Vector3d derivative(double u) const noexcept override { return {-r * std::sin(u), r * std::cos(u), pitch}; }
  double length() const { return std::sqrt(r * r + pitch * pitch) * (u1 - u0); }
};

/// Cubic Bezier in space with control points p[0..3], u in [0, 1].
struct Bezier3 : ParametricCurve {
  Eigen::Vector3d p[4];
  double u_begin() const noexcept override { return 0; }
  double u_end() const noexcept override { return 1; }
  Eigen::Vector3d position(double u) const noexcept override {
    const double v = 1 - u;
    return v * v * v * p[0] + 3 * v * v * u * p[1] + 3 * v * u * u * p[2] + u * u * u * p[3];
  }
  Eigen::Vector3d derivative(double u) const noexcept override {
    const double v = 1 - u;
    return 3 * v * v * (p[1] - p[0]) + 6 * v * u * (p[2] - p[1]) + 3 * u * u * (p[3] - p[2]);
  }
  static Bezier3 random(std::mt19937& rng) {
    std::uniform_real_distribution<double> coord(-2, 2);
    Bezier3 b;
    for (auto& q : b.p) q = {coord(rng), coord(rng), coord(rng)};
    return b;
  }
};

}  // namespace avar::playback::testing
