#pragma once
// Fitting time-stamped samples with few Bezier keys (Parent, Computer Animation, 3.4; in the
// spirit of Schneider's "An algorithm for automatically fitting digitized curves"): start from
// the end points (and the sharp corners), fit, and split every segment whose worst sample is
// over the tolerance at that sample, until every sample is within it; then drop, one by one, every
// key (other than the ends and corners) without which the curve still stays within it.
//
// Shape of the result: keys sit on samples (value = the sample's value), every key is Bezier
// with free handles a third of the segment away in time, so time runs linearly inside every
// segment (always monotone) and each segment is the cubic Hermite piece of its end slopes. The
// slopes of all keys are solved together by linear least squares over every sample, one slope
// per smooth key (tangent-continuous curve) and separate in and out slopes at corners. The
// tolerance is checked on the built Curve itself (Curve::build and evaluate, as playback
// evaluates it), so the guarantee holds for what plays. Offline: allocates.

#include <cstddef>
#include <span>
#include <vector>

#include "avar/core/input_error.hpp"
#include "avar/playback/runtime/curve.hpp"

namespace avar::playback {

struct CurveFitOptions {
  double tolerance = 0;      ///< largest allowed |curve(t_i) - v_i|, channel units, > 0
  bool keep_corners = true;  ///< split at sharp corners with broken tangents
  /// A sample is a corner when the chords to its two neighbours turn by more than this angle
  /// (degrees), measured with the data's time span and value range scaled to a square, and the
  /// slope change is significant: |v_{i+1} - 2 v_i + v_{i-1}| (for even spacing; in general the
  /// slope change times the shorter neighbouring interval) above 4 x tolerance, so noise that the
  /// tolerance covers never makes corners.
  double corner_angle_deg = 60;
};

struct [[nodiscard]] CurveFitResult {
  RawCurve curve;                        ///< Bezier keys, free handles; build it with Curve::build
  std::vector<std::size_t> key_samples;  ///< the sample index of every key
  std::vector<std::size_t> corners;      ///< the sample indices kept as corners
  double max_error = 0;                  ///< largest |built curve(t_i) - v_i| over all samples
};

/// Fits `values` sampled at `times` (seconds, strictly increasing, finite; values finite; the
/// same count, at least one). Keys and the curve carry `where`. Throws std::invalid_argument on
/// input that breaks these preconditions or a tolerance not above 0.
CurveFitResult fit_curve(std::span<const double> times, std::span<const double> values, const CurveFitOptions& options,
                         const SourceLocation& where = {});

/// The corner samples as CurveFitOptions defines them (interior samples only).
std::vector<std::size_t> find_corners(std::span<const double> times, std::span<const double> values,
                                      const CurveFitOptions& options);

}  // namespace avar::playback
