#include "avar/device/easing_fixed.hpp"

#include "avar/device/fixed_math.hpp"
#include "avar/device/show_image.hpp"

// A build without the easings (config.hpp) compiles none of this.
#if AVAR_DEVICE_EASINGS

namespace avar {
namespace device {
namespace {

const int64_t kHalf = kQ30 / 2;

int64_t power(int64_t t, int p) {
  int64_t r = kQ30;
  for (int i = 0; i < p; ++i) r = mul_q30(r, t);
  return r;
}
int64_t poly_in(int64_t t, int p) { return power(t, p); }
int64_t poly_out(int64_t t, int p) {
  const int64_t r = power(t - kQ30, p);
  return p % 2 ? r + kQ30 : kQ30 - r;
}
int64_t poly_in_out(int64_t t, int p) {
  t *= 2;
  if (t < kQ30) return power(t, p) / 2;
  t -= 2 * kQ30;
  const int64_t r = power(t, p);
  return p % 2 ? (r + 2 * kQ30) / 2 : (2 * kQ30 - r) / 2;
}

// 7.5625 and the pieces' bounds and centres (n / 2.75), Q30.
const int64_t kBounceScale = 8120172544;
const int64_t kBounce1 = 390451572;    // 1 / 2.75
const int64_t kBounce2 = 780903145;    // 2 / 2.75
const int64_t kBounce25 = 976128931;   // 2.5 / 2.75
const int64_t kBounceC1 = 585677359;   // 1.5 / 2.75
const int64_t kBounceC2 = 878516038;   // 2.25 / 2.75
const int64_t kBounceC3 = 1024935377;  // 2.625 / 2.75
int64_t bounce_out(int64_t t) {
  if (t < kBounce1) return mul_q30(kBounceScale, mul_q30(t, t));
  if (t < kBounce2) {
    t -= kBounceC1;
    return mul_q30(kBounceScale, mul_q30(t, t)) + kQ30 * 3 / 4;
  }
  if (t < kBounce25) {
    t -= kBounceC2;
    return mul_q30(kBounceScale, mul_q30(t, t)) + kQ30 * 15 / 16;
  }
  t -= kBounceC3;
  return mul_q30(kBounceScale, mul_q30(t, t)) + kQ30 * 63 / 64;
}
int64_t bounce_in(int64_t t) { return kQ30 - bounce_out(kQ30 - t); }

// Blender scales 2^(10 (t - 1)) to start at exactly 0 and end at exactly 1.
const int64_t kPowMin = kQ30 >> 10;
const int64_t kPowScale = 1074791425;  // 1 / (1 - 2^-10), Q30
int64_t expo_in(int64_t t) { return t == 0 ? 0 : mul_q30(exp2_q30(10 * (t - kQ30)) - kPowMin, kPowScale); }
int64_t expo_out(int64_t t) { return t == 0 ? 0 : kQ30 - mul_q30(exp2_q30(-10 * t) - kPowMin, kPowScale); }

int64_t sqrt_q30(int64_t x) { return x <= 0 ? 0 : static_cast<int64_t>(isqrt64(static_cast<uint64_t>(x) << 30)); }
int64_t circ_in(int64_t t) { return kQ30 - sqrt_q30(kQ30 - mul_q30(t, t)); }
int64_t circ_out(int64_t t) {
  t -= kQ30;
  return sqrt_q30(kQ30 - mul_q30(t, t));
}

int64_t back(uint8_t easing, int64_t t, int64_t o) {
  switch (easing) {
    case kEaseIn: return mul_q30(mul_q30(t, t), mul_q30(o + kQ30, t) - o);
    case kEaseInOut: {
      o = o * 1525 / 1000;
      t *= 2;
      if (t < kQ30) return mul_q30(mul_q30(t, t), mul_q30(o + kQ30, t) - o) / 2;
      t -= 2 * kQ30;
      return (mul_q30(mul_q30(t, t), mul_q30(o + kQ30, t) + o) + 2 * kQ30) / 2;
    }
    default: t -= kQ30; return mul_q30(mul_q30(t, t), mul_q30(o + kQ30, t) + o) + kQ30;
  }
}

}  // namespace

int64_t ease_fraction_q30(uint8_t kind, uint8_t easing, int64_t t, int64_t back_q30) {
  const bool in = easing == kEaseIn, out = easing == kEaseOut;
  switch (kind) {
    case kSine: {
      // A quarter turn is 2^30 in Q32 turns: t (Q30) of a quarter turn is t itself.
      if (in) return kQ30 - cos_turns(static_cast<uint32_t>(t));
      if (out) return sin_turns(static_cast<uint32_t>(t));
      return (kQ30 - cos_turns(static_cast<uint32_t>(t) << 1)) / 2;
    }
    case kQuad:
      if (in) return mul_q30(t, t);
      if (out) return -mul_q30(t, t - 2 * kQ30);
      return t < kHalf ? 2 * mul_q30(t, t) : -(mul_q30(2 * t - kQ30, 2 * t - 3 * kQ30) - kQ30) / 2;
    case kCubicEase: return in ? poly_in(t, 3) : out ? poly_out(t, 3) : poly_in_out(t, 3);
    case kQuart: return in ? poly_in(t, 4) : out ? poly_out(t, 4) : poly_in_out(t, 4);
    case kQuint: return in ? poly_in(t, 5) : out ? poly_out(t, 5) : poly_in_out(t, 5);
    case kExpo:
      if (in) return expo_in(t);
      if (out) return expo_out(t);
      return t <= kHalf ? expo_in(2 * t) / 2 : kHalf + expo_out(2 * t - kQ30) / 2;
    case kCirc:
      if (in) return circ_in(t);
      if (out) return circ_out(t);
      return t < kHalf ? circ_in(2 * t) / 2 : kHalf + circ_out(2 * t - kQ30) / 2;
    case kBack: return back(easing, t, back_q30);
    case kBounce:
      if (in) return bounce_in(t);
      if (out) return bounce_out(t);
      return t < kHalf ? bounce_in(2 * t) / 2 : kHalf + bounce_out(2 * t - kQ30) / 2;
    default: return t;
  }
}

// Blender's elastic, in units of the segment's duration: the wave at signed time u (<= 0, from
// the segment's end) is amplitude 2^(10 u) sin(2 pi (u - s) / period), and with the blend the
// factor f eases from 1 to amplitude / |change| over the first s of reach |u|.
ElasticSegment elastic_segment(uint8_t easing, int64_t change, bool blended, int64_t factor_or_amplitude, uint64_t period,
                               int64_t shift) {
  ElasticSegment e;
  e.easing = easing;
  e.change = change;
  e.blended = blended;
  e.factor = blended ? factor_or_amplitude : kQ30;
  e.amplitude = blended ? change : factor_or_amplitude;
  e.shift = shift;
  e.per_period = period == 0 ? 0 : (static_cast<uint64_t>(1) << 62) / period;
  const int64_t reach = shift < 0 ? -shift : shift;
  e.per_shift = reach == 0 ? 0 : (static_cast<uint64_t>(1) << 60) / static_cast<uint64_t>(reach);
  return e;
}

namespace {

// f * wave(u), Q8, u in Q30 (<= 0).
int64_t elastic_wave(const ElasticSegment& e, int64_t u) {
  int64_t f = e.factor;
  if (e.blended && e.change != 0) {
    const int64_t reach = -u;
    const int64_t limit = e.shift < 0 ? -e.shift : e.shift;
    if (reach < limit) {
      const int64_t l = static_cast<int64_t>((static_cast<uint64_t>(reach) * e.per_shift) >> 30);
      f = mul_q30(f, l) + (kQ30 - l);
    }
  }
  // The phase (u - s) / period in turns, Q32, kept modulo one turn (the bits above are whole turns).
  const uint64_t product = static_cast<uint64_t>(u - e.shift) * e.per_period;
  const auto phase = static_cast<uint32_t>(product >> 30);
  const int64_t wave = mul_q30(exp2_q30(10 * u), sin_turns(phase));
  return mul_q30(mul_q30(e.amplitude, wave), f);
}

}  // namespace

int64_t elastic_offset_q8(const ElasticSegment& e, int64_t t) {
  if (t == 0) return 0;
  switch (e.easing) {
    case kEaseIn: return -elastic_wave(e, t - kQ30);
    case kEaseInOut: {
      const int64_t u = 2 * t - kQ30;
      if (u < 0) return -elastic_wave(e, u) / 2;
      return elastic_wave(e, -u) / 2 + e.change;
    }
    default: return elastic_wave(e, -t) + e.change;
  }
}

}  // namespace device
}  // namespace avar

#endif  // AVAR_DEVICE_EASINGS
