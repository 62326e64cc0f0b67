#include "avar/playback/runtime/easing.hpp"

#include <cmath>
#include <numbers>

#include "avar/core/portable_math.hpp"

namespace avar::playback {
namespace {

constexpr double kPi = std::numbers::pi;

// Each function: t in [0, 1] the normalised time; returns the eased fraction of the change,
// except elastic and bounce-in-out, which need the segment's own numbers (see below).
double poly_in(double t, int power) noexcept {
  double r = 1;
  for (int i = 0; i < power; ++i) r *= t;
  return r;
}
double poly_out(double t, int power) noexcept {
  const double r = poly_in(t - 1, power);
  return power % 2 ? r + 1 : 1 - r;
}
double poly_in_out(double t, int power) noexcept {
  t *= 2;
  if (t < 1) return poly_in(t, power) / 2;
  t -= 2;
  const double r = poly_in(t, power);
  return power % 2 ? (r + 2) / 2 : (2 - r) / 2;
}

double bounce_out(double t) noexcept {
  constexpr double k = 7.5625;
  if (t < 1 / 2.75) return k * t * t;
  if (t < 2 / 2.75) {
    t -= 1.5 / 2.75;
    return k * t * t + 0.75;
  }
  if (t < 2.5 / 2.75) {
    t -= 2.25 / 2.75;
    return k * t * t + 0.9375;
  }
  t -= 2.625 / 2.75;
  return k * t * t + 0.984375;
}
double bounce_in(double t) noexcept { return 1 - bounce_out(1 - t); }

// Blender scales 2^(10 (t - 1)) so that it starts at exactly 0 and ends at exactly 1.
constexpr double kPowMin = 0.0009765625;  // 2^-10
constexpr double kPowScale = 1.0 / (1.0 - kPowMin);
double expo_in(double t) noexcept { return t == 0 ? 0 : (pmath::exp2(10 * (t - 1)) - kPowMin) * kPowScale; }
double expo_out(double t) noexcept { return t == 0 ? 0 : 1 - (pmath::exp2(-10 * t) - kPowMin) * kPowScale; }

double circ_in(double t) noexcept { return 1 - std::sqrt(std::max(0.0, 1 - t * t)); }
double circ_out(double t) noexcept {
  t -= 1;
  return std::sqrt(std::max(0.0, 1 - t * t));
}

// Elastic, in Blender's form: `u` is the signed time from the segment end in units of the
// duration (negative before it), the oscillation uses the period in seconds, and an amplitude
// below |change| blends the oscillation in near the crossing point ("elastic blend").
double elastic_wave(double u, double change, double duration, double amplitude, double period, double& f) noexcept {
  double s;
  if (amplitude == 0 || amplitude < std::abs(change)) {
    s = period / 4;
    if (change != 0) {
      f = amplitude != 0 ? f * amplitude / std::abs(change) : 0.0;
      const double reach = std::abs(u * duration);
      if (reach < std::abs(s)) {
        const double l = reach / std::abs(s);
        f = f * l + (1 - l);
      }
    }
    amplitude = change;
  } else {
    s = period / (2 * kPi) * pmath::asin(change / amplitude);
  }
  return amplitude * pmath::exp2(10 * u) * pmath::sin((u * duration - s) * (2 * kPi) / period);
}

double elastic(Easing e, double time, double begin, double change, double duration, double amplitude, double period) noexcept {
  if (time == 0) return begin;
  double f = 1;
  switch (e) {
    case Easing::ease_in: {
      const double t = time / duration;
      if (t == 1) return begin + change;
      if (period == 0) period = duration * 0.3;
      const double w = elastic_wave(t - 1, change, duration, amplitude, period, f);
      return -f * w + begin;
    }
    case Easing::ease_in_out: {
      double t = time / (duration / 2);
      if (t == 2) return begin + change;
      t -= 1;
      if (period == 0) period = duration * (0.3 * 1.5);
      if (t < 0) {
        const double w = elastic_wave(t, change, duration, amplitude, period, f);
        return -0.5 * f * w + begin;
      }
      const double w = elastic_wave(-t, change, duration, amplitude, period, f);
      return 0.5 * f * w + change + begin;
    }
    case Easing::automatic:
    case Easing::ease_out:
    default: {
      const double t = time / duration;
      if (t == 1) return begin + change;
      if (period == 0) period = duration * 0.3;
      const double w = elastic_wave(-t, change, duration, amplitude, period, f);
      return f * w + change + begin;
    }
  }
}

double back(Easing e, double t, double overshoot) noexcept {
  switch (e) {
    case Easing::ease_in: return t * t * ((overshoot + 1) * t - overshoot);
    case Easing::ease_in_out: {
      overshoot *= 1.525;
      t *= 2;
      if (t < 1) return t * t * ((overshoot + 1) * t - overshoot) / 2;
      t -= 2;
      return (t * t * ((overshoot + 1) * t + overshoot) + 2) / 2;
    }
    default: t -= 1; return t * t * ((overshoot + 1) * t + overshoot) + 1;
  }
}

// Fraction of the change for the families that scale with it.
double fraction(Interpolation family, Easing e, double t, const EasingParams& p) noexcept {
  const bool in = e == Easing::ease_in, out = e == Easing::ease_out;
  switch (family) {
    case Interpolation::sine:
      return in ? 1 - pmath::cos(t * kPi / 2) : out ? pmath::sin(t * kPi / 2) : -(pmath::cos(kPi * t) - 1) / 2;
    case Interpolation::quad:
      return in ? t * t : out ? -t * (t - 2) : (t < 0.5 ? 2 * t * t : -((2 * t - 1) * (2 * t - 3) - 1) / 2);
    case Interpolation::cubic: return in ? poly_in(t, 3) : out ? poly_out(t, 3) : poly_in_out(t, 3);
    case Interpolation::quart: return in ? poly_in(t, 4) : out ? poly_out(t, 4) : poly_in_out(t, 4);
    case Interpolation::quint: return in ? poly_in(t, 5) : out ? poly_out(t, 5) : poly_in_out(t, 5);
    case Interpolation::expo:
      return in ? expo_in(t) : out ? expo_out(t) : (t <= 0.5 ? expo_in(2 * t) / 2 : 0.5 + expo_out(2 * t - 1) / 2);
    case Interpolation::circ:
      return in ? circ_in(t) : out ? circ_out(t) : (t < 0.5 ? circ_in(2 * t) / 2 : 0.5 + circ_out(2 * t - 1) / 2);
    case Interpolation::back: return back(e, t, p.back);
    case Interpolation::bounce:
      return in ? bounce_in(t) : out ? bounce_out(t) : (t < 0.5 ? bounce_in(2 * t) / 2 : 0.5 + bounce_out(2 * t - 1) / 2);
    default: return t;
  }
}

}  // namespace

Easing resolved_easing(Interpolation family, Easing requested) noexcept {
  if (requested != Easing::automatic) return requested;
  switch (family) {
    case Interpolation::back:
    case Interpolation::bounce:
    case Interpolation::elastic: return Easing::ease_out;
    default: return Easing::ease_in;
  }
}

double ease(Interpolation family, Easing easing, double time, double begin, double change, double duration,
            const EasingParams& params) noexcept {
  if (family == Interpolation::elastic) return elastic(easing, time, begin, change, duration, params.amplitude, params.period);
  return begin + change * fraction(family, easing, time / duration, params);
}

}  // namespace avar::playback
