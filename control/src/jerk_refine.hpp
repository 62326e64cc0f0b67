#pragma once
// The solve's last stage: safeguarded Newton inside the bracket, to rounding.

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>

#include "jerk_bracket.hpp"
#include "jerk_branches.hpp"
#include "jerk_residuals.hpp"

namespace avar::control::jerk {

/// Bound of the bracketed refinement (each one evaluation of D).
inline constexpr int kMaxRefinements = 64;
/// A plan whose end misses the goal by at most this many rounding tolerances is shifted onto it.
inline constexpr double kShiftable = 64;

/// Safeguarded Newton in `br`: a step that leaves the bracket becomes a regula falsi or bisection.
/// Near vp = natural the distance grows like a square root of vp, so the bracket may close
/// before the residual does: an end of the bracket that falls short of the goal in the
/// direction it moves is finished exactly by a short cruise at its velocity (time-optimal but
/// for that cruise, which is accepted once negligible: `negligible_s`, s). Starts from the warm
/// start's last iterate (`resume`) inside the bracket; always ends the solve in `out`.
[[gnu::always_inline]] inline void refine(Bracket br, double resume, double negligible_s, const Branches& b, Residuals& residual,
                                          Solution& out) {
  double lo = br.lo, hi = br.hi, f_lo = br.f_lo, f_hi = br.f_hi;
  const double natural = b.natural;
  const auto finish_short = [&](double x, double f) {
    if (x == 0 || -f / x < 0 || -f / x > negligible_s) return false;
    out.vp = x;
    out.cruise = -f / x;
    return true;
  };
  const double tolerance = residual.tolerance();
  if (!out.found() && std::abs(f_lo) <= tolerance) out.vp = lo;
  if (!out.found() && std::abs(f_hi) <= tolerance) out.vp = hi;
  if (out.found() || finish_short(lo, f_lo) || finish_short(hi, f_hi)) return;
  // Next to the natural velocity D grows like the square root of |vp - natural|: there the
  // iteration runs in u = sqrt(|vp - natural|), in which D is smooth.
  const CornerMap map{!br.warm && b.cornered(lo, hi), natural, lo == natural ? 1.0 : -1.0};
  double u_lo = map.to_u(lo), u_hi = map.to_u(hi);
  const auto inside = [&](double u) { return (u - u_lo) * (u - u_hi) < 0; };
  const auto secant = [&] { return u_lo - f_lo * (u_hi - u_lo) / (f_hi - f_lo); };
  // The warm start's last iterate; else, between 0 and the natural velocity, the model; else
  // a Newton step from an end; else the secant.
  const bool resume_inside = (resume - lo) * (resume - hi) < 0;
  const bool model_inside = (br.model - lo) * (br.model - hi) < 0;
  double u = resume_inside ? map.to_u(resume) : model_inside ? map.to_u(br.model) : secant();
  if (!resume_inside && !model_inside) {
    // A Newton step from the end with the smaller residual (in u where mapped).
    const auto newton_from = [&](double x, double f, double slope) {
      const double ux = map.to_u(x);
      if (!(slope > 0) || !std::isfinite(slope) || (map.mapped && !(ux > 0))) return std::numeric_limits<double>::quiet_NaN();
      return ux - f / map.slope(slope, ux);
    };
    const double start =
        std::abs(f_lo) <= std::abs(f_hi) ? newton_from(lo, f_lo, br.slope_lo) : newton_from(hi, f_hi, br.slope_hi);
    if (inside(start)) u = start;
  }
  if (!inside(u)) u = 0.5 * (u_lo + u_hi);
  bool bisect = false;
  double previous_x = std::numeric_limits<double>::quiet_NaN();
  for (int k = 0; k < kMaxRefinements; ++k) {
    const double x = map.to_vp(u);
    const Reach r = residual(x);
    if (residual.accept(x, r, out)) break;
    // In u, steps can go on shrinking the bracket's far side while vp = natural ± u² no
    // longer changes at all (its last bit is reached): the residual is then as small as vp's
    // resolution allows. Accept it when the end shift may absorb it; otherwise stop
    // (the fallback after the loop keeps the plan exact). Without this the loop ran to its
    // bound on the same vp (issue: 64 evaluations a tick on some moving-target states).
    if (x == previous_x) {
      if (std::abs(r.distance) <= kShiftable * residual.tolerance()) out.vp = x;
      break;
    }
    previous_x = x;
    if (r.distance < 0) {
      lo = x, u_lo = u, f_lo = r.distance;
    } else {
      hi = x, u_hi = u, f_hi = r.distance;
    }
    if (finish_short(x, r.distance)) break;
    if (std::abs(u_hi - u_lo) <= 2 * DBL_EPSILON * std::max(std::abs(u_lo), std::abs(u_hi))) break;
    double next = u - r.distance / map.slope(r.slope, u);
    if (!inside(next) || next == u) {
      next = bisect ? 0.5 * (u_lo + u_hi) : secant();
      if (!inside(next)) next = 0.5 * (u_lo + u_hi);
      bisect = !bisect;
    }
    u = next;
  }
  if (!out.found() && lo > 0) {
    out.vp = lo;
    out.cruise = -f_lo / lo;
  } else if (!out.found() && hi < 0) {
    out.vp = hi;
    out.cruise = -f_hi / hi;
  } else if (!out.found()) {
    out.vp = 0.5 * (lo + hi);
  }
}

}  // namespace avar::control::jerk
