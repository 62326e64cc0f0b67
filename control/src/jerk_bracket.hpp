#pragma once
// The solve's second stage: the branch that holds the root, bracketed, with a start inside it.

#include <cmath>
#include <limits>

#include "jerk_branches.hpp"
#include "jerk_residuals.hpp"
#include "jerk_start_models.hpp"
#include "jerk_warm_start.hpp"

namespace avar::control::jerk {

/// The branch that holds the root, bracketed as f(lo) <= 0 <= f(hi).
struct Bracket {
  double lo = 0, hi = 0, f_lo = 0, f_hi = 0;
  /// The slope at a bracket end next to the root's side of 0 or the natural velocity, where
  /// the residual is often far smaller than at ±V: a Newton step from there starts the solve.
  double slope_lo = 0, slope_hi = 0;
  /// Between 0 and the natural velocity: where model_from puts the root, from the end nearer it.
  double model = std::numeric_limits<double>::quiet_NaN();
  bool warm = false;  ///< the warm start's points are the bracket

  void set_lo(double x, const Reach& r) { lo = x, f_lo = r.distance, slope_lo = r.slope; }
  void set_hi(double x, const Reach& r) { hi = x, f_hi = r.distance, slope_hi = r.slope; }
};

/// A probe that falls short of the goal on the way to `end` (V or -V): one Newton step from it
/// (it usually lands close) before `end` is evaluated. True when the step ends the solve or
/// brackets the root with the probe; otherwise a step still short becomes short_x, at_short.
inline bool step_from_probe(double probe, const Reach& at_probe, double end, double& short_x, Reach& at_short,
                            Residuals& residual, Bracket& br, Solution& out) {
  const double step = at_probe.slope > 0 ? probe - at_probe.distance / at_probe.slope : probe;
  if (!((step - probe) * (step - end) < 0)) return false;
  const Reach at_step = residual(step);
  if (residual.accept(step, at_step, out)) return true;
  if ((at_step.distance >= 0) != (end > 0)) {
    short_x = step, at_short = at_step;
    return false;
  }
  const bool up = step > probe;
  br.set_lo(up ? probe : step, up ? at_probe : at_step);
  br.set_hi(up ? step : probe, up ? at_step : at_probe);
  return true;
}

/// Brackets the root after the warm start `w`: from the warm start's points, or from the branch
/// ends (high first, unless the warm start pointed below low), probing by the start models before
/// evaluating ±V. May end the solve in `out` instead (a probe on the root, or ±V short of the goal:
/// the cruise fills the rest).
[[gnu::always_inline]] inline Bracket bracket_root(const WarmStart& w, double V, const JerkLimits& limits, const Branches& b,
                                                   const Bounds& bounds, Residuals& residual, Solution& out) {
  const double low = b.low, high = b.high;
  Bracket br;
  br.warm = w.brackets();
  // high is evaluated first, unless the warm start pointed below low: then low is, and high
  // only if the root is not below low after all.
  const bool low_first = !br.warm && low != high && w.pointed < low;
  const bool root_below_low = low_first && residual(low).distance >= 0;
  const Reach at_high = br.warm || root_below_low ? Reach{} : residual(high);
  if (br.warm) {
    br.lo = w.below, br.f_lo = w.f_below, br.hi = w.above, br.f_hi = w.f_above;
  } else if (!root_below_low && at_high.distance <= 0) {
    // The root is in [high, V]. First the model: brake (or release) to `high`, then the rest
    // of the distance as a move from rest; it usually brackets the root with `high` and spares
    // the evaluation at V.
    const double probe = model_from(b, high, at_high, true, limits, bounds);
    const bool probed = probe > high && probe < V;
    const Reach at_probe = probed ? residual(probe) : at_high;
    if (probed && residual.accept(probe, at_probe, out)) {
      // (the probe is on the root)
    } else if (probed && at_probe.distance >= 0) {
      br.set_lo(high, at_high);
      br.set_hi(probe, at_probe);
    } else {
      double short_x = probed ? probe : high;
      Reach at_short = at_probe;
      if (!(probed && step_from_probe(probe, at_probe, V, short_x, at_short, residual, br, out))) {
        const Reach at_v = residual(V);
        if (at_v.distance <= 0) {
          out.vp = V;
          out.cruise = -at_v.distance / V;
        }
        br.set_lo(short_x, at_short);
        br.hi = V, br.f_hi = at_v.distance;
      }
    }
  } else {
    const Reach at_low = low == high ? at_high : residual(low);
    if (at_low.distance >= 0) {
      // The root is in [-V, low]: as above, mirrored.
      const double probe = model_from(b, low, at_low, true, limits, bounds);
      const bool probed = probe < low && probe > -V;
      const Reach at_probe = probed ? residual(probe) : at_low;
      if (probed && residual.accept(probe, at_probe, out)) {
        // (the probe is on the root)
      } else if (probed && at_probe.distance <= 0) {
        br.set_lo(probe, at_probe);
        br.set_hi(low, at_low);
      } else {
        double short_x = probed ? probe : low;
        Reach at_short = at_probe;
        if (!(probed && step_from_probe(probe, at_probe, -V, short_x, at_short, residual, br, out))) {
          const Reach at_minus_v = residual(-V);
          if (at_minus_v.distance >= 0) {
            out.vp = -V;
            out.cruise = at_minus_v.distance / V;
          }
          br.lo = -V, br.f_lo = at_minus_v.distance;
          br.set_hi(short_x, at_short);
        }
      }
    } else {
      br.set_lo(low, at_low);
      br.set_hi(high, at_high);
      // D need not be monotone here, so the end with the smaller residual need not be the
      // nearer one: the braking model, where it applies, first (it checks its own range).
      br.model = braking_model(b, low == 0 ? at_low : at_high, bounds);
      if (!(br.model == br.model))
        br.model = std::abs(at_low.distance) <= std::abs(at_high.distance) ? model_from(b, low, at_low, false, limits, bounds)
                                                                           : model_from(b, high, at_high, false, limits, bounds);
    }
  }
  return br;
}

}  // namespace avar::control::jerk
