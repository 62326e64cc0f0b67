#include "avar/control/jerk_profile.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>

namespace avar::control {
namespace {

/// The time-optimal change from (v0, a0) to (v1, 0) with |a| <= A: jerk s·J until the
/// acceleration reaches s·peak, a hold there (only at peak = A), jerk -s·J back to zero.
struct VelocityChange {
  double s = 1;         ///< +1 raises the velocity past its natural value v0 + a0|a0|/(2J), -1 lowers it
  double peak = 0;      ///< |peak acceleration|, <= A
  double rise = 0;      ///< s (duration of the first jerk piece)
  double hold = 0;      ///< s
  double fall = 0;      ///< s
  double distance = 0;  ///< units
};

VelocityChange velocity_change(double v0, double a0, double v1, double A, double J) {
  VelocityChange c;
  c.s = v1 >= v0 + a0 * std::abs(a0) / (2 * J) ? 1.0 : -1.0;
  // In the frame where the change raises the velocity: w = s v, b = s a.
  const double b0 = c.s * a0;
  const double w0 = c.s * v0;
  const double dw = c.s * (v1 - v0);
  // Velocity gained: (peak² - b0²)/(2J) rising, peak·hold, peak²/(2J) falling.
  const double peak_squared = std::max(0.0, J * dw + 0.5 * b0 * b0);
  if (peak_squared <= A * A) {
    c.peak = std::sqrt(peak_squared);
  } else {
    c.peak = A;
    c.hold = std::max(0.0, (dw - (2 * A * A - b0 * b0) / (2 * J)) / A);
  }
  // peak >= b0 but for rounding, which would leave the change ending with a != 0.
  c.peak = std::max(c.peak, b0);
  c.rise = (c.peak - b0) / J;
  c.fall = c.peak / J;
  const double t1 = c.rise, t2 = c.hold, t3 = c.fall, m = c.peak;
  double w = w0;
  double x = w * t1 + b0 * t1 * t1 / 2 + J * t1 * t1 * t1 / 6;
  w += b0 * t1 + J * t1 * t1 / 2;
  x += w * t2 + m * t2 * t2 / 2;
  w += m * t2;
  x += w * t3 + m * t3 * t3 / 2 - J * t3 * t3 * t3 / 6;
  c.distance = c.s * x;
  return c;
}

/// The peak acceleration of the time-optimal stop from (v, 0): sqrt(J|v|), at most A.
double stop_peak(double v, double A, double J) { return std::min(std::sqrt(J * std::abs(v)), A); }

/// Distance of phase 1 (to vp) plus the stop from (vp, 0), and its slope d/dvp: for a change to
/// v1 with peak m, d distance/d v1 = s v1/m + m/(2J); the stop from vp covers vp T/2 with
/// T = m/J + |vp|/m, of slope |vp|/m + m/(2J).
struct Reach {
  double distance = 0;
  double slope = 0;
};

Reach reach(double v0, double a0, double vp, double A, double J) {
  const VelocityChange c = velocity_change(v0, a0, vp, A, J);
  Reach r;
  r.distance = c.distance;
  r.slope = c.peak > 0 ? c.s * vp / c.peak + c.peak / (2 * J) : std::numeric_limits<double>::infinity();
  const double m = stop_peak(vp, A, J);
  if (m > 0) {
    r.distance += vp * (m / J + std::abs(vp) / m) / 2;
    r.slope += std::abs(vp) / m + m / (2 * J);
  }
  return r;
}

MotionState advance(MotionState s, double t, double jerk) {
  s.p += t * (s.v + t * (s.a / 2 + t * jerk / 6));
  s.v += t * (s.a + t * jerk / 2);
  s.a += t * jerk;
  return s;
}

}  // namespace

double stopping_point(const MotionState& s, const JerkLimits& limits) noexcept {
  const double a = std::clamp(s.a, -limits.acceleration, limits.acceleration);
  return s.p + velocity_change(s.v, a, 0, limits.acceleration, limits.jerk).distance;
}

void JerkProfile::plan(const MotionState& from, double goal, const JerkLimits& limits, double hint) noexcept {
  const double V = limits.velocity, A = limits.acceleration, J = limits.jerk;
  start_ = {from.p, from.v, std::clamp(from.a, -A, A)};
  goal_ = goal;
  const double v0 = start_.v, a0 = start_.a;
  const double d = goal - from.p;
  // Reached to rounding: the last bits of the distance are what the plan's end may miss by.
  const double tolerance = 4 * DBL_EPSILON * (std::abs(from.p) + std::abs(goal)) + DBL_MIN;
  const auto residual = [&](double vp) {
    Reach r = reach(v0, a0, vp, A, J);
    r.distance -= d;
    return r;
  };

  // D is increasing for vp beyond both the natural velocity (reached by releasing the
  // acceleration) and 0; between them (a change and a stop in the same direction) it may not be.
  const double natural = std::clamp(v0 + a0 * std::abs(a0) / (2 * J), -V, V);
  const double low = std::min(natural, 0.0), high = std::max(natural, 0.0);

  double vp = std::numeric_limits<double>::quiet_NaN();
  double cruise = 0;
  // A re-plan toward the same goal from a state on the last plan has the same peak: try it
  // first, with a few Newton steps kept on its monotone branch.
  if (std::isfinite(hint) && (hint >= high || hint <= low)) {
    const double lo = hint >= high ? high : -V, hi = hint >= high ? V : low;
    double x = std::clamp(hint, lo, hi);
    for (int k = 0; k < 3; ++k) {
      const Reach r = residual(x);
      if (std::abs(x) == V && r.distance * x <= 0) {
        vp = x;
        cruise = -r.distance / x;
        break;
      }
      if (std::abs(r.distance) <= tolerance) {
        vp = x;
        break;
      }
      const double next = std::clamp(x - r.distance / r.slope, lo, hi);
      if (!(next != x)) break;
      x = next;
    }
  }
  if (!(vp == vp)) {
    // The branch that holds the root, bracketed as f(lo) <= 0 <= f(hi).
    double lo = 0, hi = 0, f_lo = 0, f_hi = 0;
    const Reach at_high = residual(high);
    if (at_high.distance <= 0) {
      const Reach at_v = residual(V);
      if (at_v.distance <= 0) {
        vp = V;
        cruise = -at_v.distance / V;
      }
      lo = high, f_lo = at_high.distance, hi = V, f_hi = at_v.distance;
    } else {
      const Reach at_low = low == high ? at_high : residual(low);
      if (at_low.distance >= 0) {
        const Reach at_minus_v = residual(-V);
        if (at_minus_v.distance >= 0) {
          vp = -V;
          cruise = at_minus_v.distance / V;
        }
        lo = -V, f_lo = at_minus_v.distance, hi = low, f_hi = at_low.distance;
      } else {
        lo = low, f_lo = at_low.distance, hi = high, f_hi = at_high.distance;
      }
    }
    // Safeguarded Newton: a step that leaves the bracket becomes a regula falsi or bisection.
    // Near vp = natural the distance grows like a square root of vp, so the bracket may close
    // before the residual does: an end of the bracket that falls short of the goal in the
    // direction it moves is finished exactly by a short cruise at its velocity (time-optimal but
    // for that cruise, which is accepted once negligible).
    const double negligible_s = 1e-9 * (V / A + A / J);
    const auto finish_short = [&](double x, double f) {
      if (x == 0 || -f / x < 0 || -f / x > negligible_s) return false;
      vp = x;
      cruise = -f / x;
      return true;
    };
    if (!(vp == vp) && std::abs(f_lo) <= tolerance) vp = lo;
    if (!(vp == vp) && std::abs(f_hi) <= tolerance) vp = hi;
    if (!(vp == vp) && !finish_short(lo, f_lo) && !finish_short(hi, f_hi)) {
      double x = hint > lo && hint < hi ? hint : lo + (hi - lo) * (-f_lo / (f_hi - f_lo));
      if (!(x > lo && x < hi)) x = 0.5 * (lo + hi);
      bool bisect = false;
      for (int k = 0; k < 64; ++k) {
        const Reach r = residual(x);
        if (std::abs(r.distance) <= tolerance) {
          vp = x;
          break;
        }
        (r.distance < 0 ? lo : hi) = x;
        (r.distance < 0 ? f_lo : f_hi) = r.distance;
        if (finish_short(x, r.distance)) break;
        if (hi - lo <= 2 * DBL_EPSILON * std::max(std::abs(lo), std::abs(hi))) break;
        double next = x - r.distance / r.slope;
        if (!(next > lo && next < hi) || next == x) {
          next = bisect ? 0.5 * (lo + hi) : lo + (hi - lo) * (-f_lo / (f_hi - f_lo));
          if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
          bisect = !bisect;
        }
        x = next;
      }
      if (!(vp == vp) && lo > 0) {
        vp = lo;
        cruise = -f_lo / lo;
      } else if (!(vp == vp) && hi < 0) {
        vp = hi;
        cruise = -f_hi / hi;
      } else if (!(vp == vp)) {
        vp = 0.5 * (lo + hi);
      }
    }
  }
  peak_ = vp;

  const VelocityChange change = velocity_change(v0, a0, vp, A, J);
  const double m = stop_peak(vp, A, J);
  const double stop_jerk = vp > 0 ? -J : J;
  const double stop_ramp = m / J;
  const double stop_hold = m > 0 ? std::max(0.0, std::abs(vp) / m - m / J) : 0.0;
  pieces_ = {Piece{change.rise, change.s * J},   Piece{change.hold, 0},     Piece{change.fall, -change.s * J},
             Piece{cruise, 0},                   Piece{stop_ramp, stop_jerk}, Piece{stop_hold, 0},
             Piece{stop_ramp, -stop_jerk}};
  duration_ = 0;
  for (const Piece& piece : pieces_) duration_ += piece.duration;
  // The plan's end misses the goal by the solve's last bits: shift the whole plan onto the goal,
  // so that the position's rounding never accumulates from tick to tick (a shift larger than
  // rounding, from a solve that did not converge, is left for the next plan to correct).
  const double miss = goal - follow(duration_).p;
  offset_ = std::abs(miss) <= 64 * tolerance ? miss : 0.0;
}

MotionState JerkProfile::at(double t) const noexcept {
  if (!(t < duration_)) return {goal_, 0, 0};
  MotionState s = follow(t);
  s.p += offset_;
  return s;
}

MotionState JerkProfile::follow(double t) const noexcept {
  MotionState s = start_;
  for (std::size_t i = 0; i < kPieces; ++i) {
    if (t <= pieces_[i].duration) return advance(s, t, pieces_[i].jerk);
    s = advance(s, pieces_[i].duration, pieces_[i].jerk);
    t -= pieces_[i].duration;
    // The stop was planned from exactly (peak, 0): do not carry the change's rounding into it.
    if (i == 2 || i == 3) s.v = peak_, s.a = 0;
  }
  return s;
}

}  // namespace avar::control
