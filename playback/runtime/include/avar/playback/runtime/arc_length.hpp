#pragma once
// Arc length of parametric curves in 1-D or 3-D (Parent, Computer Animation, 3.2): the length by
// adaptive Gauss-Legendre quadrature, the parameter at a given length (the inverse) by Newton's
// method with a bisection fallback, and a precomputed table for real-time use.
//
// Error bound. The quadrature integrates the speed |c'(u)| with 5-point Gauss-Legendre rules; an
// interval is accepted when the rule on the whole interval and the sum of the rules on its halves
// agree within the interval's share of the tolerance (the share halves at each subdivision), and
// the halves' sum is returned. The halves' sum is ~2^10 times more accurate than the whole-interval
// rule for smooth speeds, so the disagreement bounds its error: the returned length is within
// `tolerance` of the true length whenever the speed is smooth (C^10 in theory, in practice any
// polynomial or trigonometric curve). Subdivision stops at depth kMaxArcLengthDepth.

#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace avar::playback {

/// A curve c(u), u in [u_begin(), u_end()], in some length unit. A 1-D curve puts its value in x
/// and leaves y and z at 0. Implementations must be pure: the functions here call them from the
/// caller's thread, and are real-time safe exactly when position() and derivative() are.
class ParametricCurve {
 public:
  virtual ~ParametricCurve() = default;
  virtual double u_begin() const noexcept = 0;
  virtual double u_end() const noexcept = 0;
  virtual Eigen::Vector3d position(double u) const noexcept = 0;
  /// dc/du at u.
  virtual Eigen::Vector3d derivative(double u) const noexcept = 0;
};

inline constexpr int kMaxArcLengthDepth = 40;

/// Length of the curve from u = a to u = b (negative when b < a), within `tolerance` (> 0, in the
/// curve's length unit; see the error bound above). No allocation or exception.
double arc_length(const ParametricCurve& curve, double a, double b, double tolerance) noexcept;

/// The parameter u in [u_begin, u_end] where the length from u_begin is `distance`, so that
/// |length(u_begin, u) - distance| <= tolerance; distance is clamped to [0, total length]. Newton
/// steps on length(u) - distance, replaced by bisection of the bracketing interval whenever a step
/// leaves it or the speed vanishes. `total_length` may be passed when known (negative: computed).
/// No allocation or exception.
double parameter_at_length(const ParametricCurve& curve, double distance, double tolerance, double total_length = -1) noexcept;

/// A table of length against parameter for real-time evaluation: the range of u is cut into 8
/// equal intervals, and each is halved at build until the cubic Hermite interpolant of the length
/// (from the lengths and speeds at the interval's ends) agrees with the quadrature within
/// `tolerance` at its middle. Only the intervals that need it are halved: a kink or a cusp of the
/// speed costs a few intervals around it, not a finer grid over the whole range. Lookups find
/// their interval by binary search. Build allocates (load time); the lookups do not allocate,
/// throw or lock, and the table is immutable, so any thread may use it.
class ArcLengthTable {
 public:
  /// Throws std::invalid_argument when tolerance is not above 0 or the range is empty or not
  /// finite. No interval is made narrower than the range / max_intervals (one that still misses
  /// the bound there is kept as it is).
  ArcLengthTable(const ParametricCurve& curve, double tolerance, std::size_t max_intervals = 1u << 16);

  double total_length() const noexcept { return lengths_.back(); }
  double u_begin() const noexcept { return u0_; }
  double u_end() const noexcept { return u1_; }
  std::size_t intervals() const noexcept { return knots_.size() - 1; }

  /// Length from u_begin to u (u clamped into the range).
  double length_at(double u) const noexcept;
  /// The parameter where the length from u_begin is `distance` (clamped to [0, total_length()]):
  /// binary search over the table, then the Hermite piece solved by safeguarded Newton. Monotone
  /// non-decreasing in distance.
  double parameter_at(double distance) const noexcept;

 private:
  /// Appends [last knot, b] as one interval when its Hermite piece meets the bound at its
  /// middle (or it is as narrow as allowed), else its two halves, each refined in turn.
  void refine(const ParametricCurve& curve, double b, double tolerance, double narrowest);
  /// The interval holding u (clamped to the first and last).
  std::size_t interval_of(double u) const noexcept;
  double hermite(std::size_t i, double w) const noexcept;
  double u0_ = 0, u1_ = 0;
  std::vector<double> knots_;    ///< the intervals' ends, u0 .. u1, increasing
  std::vector<double> lengths_;  ///< length from u0 at each knot
  std::vector<double> speeds_;   ///< |c'| at each knot
};

}  // namespace avar::playback
