#include "avar/device/curve_engine.hpp"

#include "avar/device/easing_fixed.hpp"
#include "avar/device/fixed_math.hpp"

namespace avar {
namespace device {
namespace {

// Bisection steps of a Bezier segment's time polynomial: u to 2^-24 (the last interval's middle
// puts it within 2^-25), 0.006 output units at the steepest value cubic the image allows.
const int kBezierSteps = 24;

struct KeyHead {
  uint8_t header;
  int32_t time;
  int32_t value;
};

// Reads a key's header, time and value; prev_* are the previous key's (ignored for the first).
KeyHead read_head(ByteReader& r, bool first, int32_t prev_time, int32_t prev_value) {
  KeyHead k;
  k.header = r.u8();
  k.time = static_cast<int32_t>(first ? r.zigzag() : prev_time + static_cast<int64_t>(r.varint()));
  k.value = static_cast<int32_t>((first ? 0 : prev_value) + r.zigzag());
  return k;
}

// Decodes the segment whose key record starts at `at` (key `index`), given the previous key's
// time and value, and reads the next key's time and value.
void load_segment(const Channel& ch, SegmentCache& c, uint32_t at, uint16_t index, int32_t prev_time, int32_t prev_value) {
  ByteReader r = {ch.image, ch.size, at, false};
  const KeyHead k = read_head(r, index == 0, prev_time, prev_value);
  c.index = index;
  c.kind = k.header & 0x1fu;
  c.easing = (k.header >> 5) & 3u;
  c.t0 = k.time;
  c.k0 = k.value;
  int64_t inner1 = 0, inner2 = 0;
  uint32_t ta = 0, tb = 0;
  int64_t param1 = 0, param3 = 0;
  uint64_t param2 = 0;
  bool blended = false;
  switch (c.kind) {
    case kCubic:
    case kBezier:
      inner1 = r.zigzag();
      inner2 = r.zigzag();
      if (c.kind == kBezier) {
        const bool wide = (k.header & kKeyWideBezier) != 0;
        if (k.header & kKeySameHandleTimes) {
          // The previous Bezier key's, still in the cache: segments load in key order from the
          // first (check_image made sure a Bezier key came before).
          ta = c.ta, tb = c.tb;
        } else {
          ta = r.fixed(wide ? 3 : 2) << (wide ? 7 : 15);  // Q23 or Q15 to Q30
          tb = r.fixed(wide ? 3 : 2) << (wide ? 7 : 15);
        }
      }
      break;
#if AVAR_DEVICE_EASINGS
    case kBack: param1 = r.zigzag(); break;
    case kElastic:
      blended = r.u8() != 0;
      param1 = r.zigzag();
      param2 = r.varint();
      param3 = r.zigzag();
      break;
#endif
    default: break;
  }
  c.next_at = r.at;
  const KeyHead next = read_head(r, false, k.time, k.value);
  c.t1 = next.time;
  c.k1 = next.value;
  // (t - t0) * reciprocal >> shift = (t - t0) 2^30 / d: reciprocal = 2^(30 + L) / d in (2^30, 2^31]
  // for d of L bits, and the product stays below 2^63.
  const uint32_t d = static_cast<uint32_t>(static_cast<int64_t>(c.t1) - c.t0);
  unsigned bits = 0;
  while (bits < 32 && (d >> bits) != 0) ++bits;
  c.shift = static_cast<uint8_t>(bits);
  c.reciprocal = static_cast<uint32_t>((static_cast<uint64_t>(1) << (30 + bits)) / d);
  const int64_t v0 = static_cast<int64_t>(c.k0) * 256,
                v1 = static_cast<int64_t>(c.k1) * 256;  // Q8 (a product: C++14 leaves a negative shifted left undefined)
  c.v0 = v0;
  c.c1 = c.c2 = c.c3 = 0;
  if (c.kind == kBezier) c.ta = ta, c.tb = tb;  // kept across other segments for the next Bezier key
#if AVAR_DEVICE_EASINGS
  c.p0 = c.p1 = c.p2 = c.p3 = 0;
  c.q0 = c.q1 = 0;
#else
  (void)blended, (void)param1, (void)param2, (void)param3;
#endif
  switch (c.kind) {
    case kStep: break;
    case kLinear: c.c1 = v1 - v0; break;
    case kCubic:
    case kBezier: {
      // Bernstein control points v0, p1, p2, v1 to the power basis.
      const int64_t p1 = v0 + inner1 * 256, p2 = v1 + inner2 * 256;
      c.c1 = 3 * (p1 - v0);
      c.c2 = 3 * (v0 - 2 * p1 + p2);
      c.c3 = v1 - v0 + 3 * (p1 - p2);
      break;
    }
#if AVAR_DEVICE_EASINGS
    case kBack:
      c.c1 = v1 - v0;
      c.p0 = param1 * 16384;  // Q16 to Q30
      break;
    case kElastic: {
      c.c1 = v1 - v0;
      const ElasticSegment e = elastic_segment(c.easing, c.c1, blended, param1, param2, param3);
      c.p0 = e.blended ? 1 : 0;
      c.p1 = e.amplitude;
      c.p2 = e.factor;
      c.p3 = e.shift;
      c.q0 = e.per_shift;
      c.q1 = e.per_period;
      break;
    }
#endif
    default: c.c1 = v1 - v0; break;
  }
  const auto magnitude = [](int64_t x) { return x < 0 ? -x : x; };
  c.narrow = magnitude(c.v0) + magnitude(c.c1) + magnitude(c.c2) + magnitude(c.c3) < (static_cast<int64_t>(1) << 31);
}

// The cubic (Q8 coefficients) at x (Q30), by Horner.
int64_t cubic_at(const SegmentCache& c, int64_t x) { return c.v0 + mul_q30(c.c1 + mul_q30(c.c2 + mul_q30(c.c3, x), x), x); }

// The parameter u (Q30) where the segment's time polynomial, with control times 0, ta, tb, 1
// (non-decreasing: the exporter checked), reaches s: de Casteljau halving, which needs only
// additions and shifts, keeping the half that holds s.
//
// The control times are kept relative to the first (d1, d2, d3, and s less it): every midpoint is
// the first plus the midpoint of the differences, so the halving is the same to the bit, and once
// the part left spans less than 2^15 the rest runs on 16-bit words (half the work on small cores).
template <typename Word>
bool bisect(Word& d1, Word& d2, Word& d3, Word& s, uint32_t& u, uint32_t& bit, int& step, bool wide) {
  for (; step < kBezierSteps; ++step, bit >>= 1) {
    if (wide && d3 < 0x8000u) return false;  // the rest in 16 bits
    const Word p01 = static_cast<Word>(d1 >> 1), p12 = static_cast<Word>((d1 + d2) >> 1), p23 = static_cast<Word>((d2 + d3) >> 1);
    const Word p012 = static_cast<Word>((p01 + p12) >> 1), p123 = static_cast<Word>((p12 + p23) >> 1);
    const Word mid = static_cast<Word>((p012 + p123) >> 1);
    // On the midpoint: its parameter (where the time polynomial is flat, the halves beyond it
    // may hold the same time to the last bit, and either end of them is off).
    if (s == mid) {
      u |= bit;
      return true;
    }
    if (s < mid) {
      d1 = p01, d2 = p012, d3 = mid;
    } else {
      s = static_cast<Word>(s - mid), d1 = static_cast<Word>(p123 - mid), d2 = static_cast<Word>(p23 - mid);
      d3 = static_cast<Word>(d3 - mid);
      u |= bit;
    }
  }
  u += static_cast<uint32_t>(1) << (29 - kBezierSteps);  // the last interval's middle
  return true;
}

int64_t bezier_parameter(const SegmentCache& c, uint32_t s) {
  uint32_t d1 = c.ta, d2 = c.tb, d3 = static_cast<uint32_t>(kQ30), rest = s;
  uint32_t u = 0, bit = static_cast<uint32_t>(1) << 29;  // this step's bit of u
  int step = 0;
  if (!bisect<uint32_t>(d1, d2, d3, rest, u, bit, step, true)) {
    uint16_t e1 = static_cast<uint16_t>(d1), e2 = static_cast<uint16_t>(d2), e3 = static_cast<uint16_t>(d3),
             r = static_cast<uint16_t>(rest);
    bisect<uint16_t>(e1, e2, e3, r, u, bit, step, false);
  }
  return static_cast<int64_t>(u);
}

// x << k for k < 32, a byte at a time first (an 8-bit core shifts a bit per instruction per byte).
uint32_t shifted_left(uint32_t x, uint8_t k) {
  for (; k >= 8; k = static_cast<uint8_t>(k - 8)) x <<= 8;
  return x << k;
}

// floor(dt 2^30 / d) for the segment's duration d = t1 - t0 and 0 <= dt < d, exactly: the
// reciprocal's estimate is at most one below it, and the remainder says which.
uint32_t normalised_time(const SegmentCache& c, uint32_t dt) {
  const uint32_t d = static_cast<uint32_t>(c.t1) - static_cast<uint32_t>(c.t0);
  if (c.shift <= 31) {
    // dt < 2^shift: shifted to the top of a word, the estimate is the high word of one
    // 32 x 32-bit product; the remainder dt 2^30 - q d lies in [0, 2d) < 2^32, so its low word
    // is all of it.
    uint32_t q = mul_wide(shifted_left(dt, static_cast<uint8_t>(32 - c.shift)), c.reciprocal).high;
    // (dt's low two bits placed at the top by a byte move and a small shift, not a loop)
    const uint32_t remainder = (static_cast<uint32_t>(static_cast<uint8_t>((static_cast<uint8_t>(dt) & 3u) << 6)) << 24) - q * d;
    if (remainder >= d) ++q;
    return q;
  }
  uint64_t q = (static_cast<uint64_t>(dt) * c.reciprocal) >> c.shift;
  if ((q + 1) * d <= (static_cast<uint64_t>(dt) << 30)) ++q;
  return static_cast<uint32_t>(q);
}

// The normalised time (Q30) of tick t of the segment, t0 <= t < t1.
uint32_t segment_time(const SegmentCache& c, int32_t t) {
  return normalised_time(c, static_cast<uint32_t>(t) - static_cast<uint32_t>(c.t0));
}

// The segment's value at tick t, t0 <= t < t1, Q8.
int64_t evaluate_in(const SegmentCache& c, int32_t t) {
  if (c.kind == kStep) return c.v0;
  const auto s = static_cast<int64_t>(segment_time(c, t));  // Q30, < 2^30
  switch (c.kind) {
    case kLinear: return c.v0 + mul_q30(c.c1, s);
    case kCubic: return cubic_at(c, s);
    case kBezier: return cubic_at(c, bezier_parameter(c, static_cast<uint32_t>(s)));
#if AVAR_DEVICE_EASINGS
    case kElastic: {
      const ElasticSegment e = {c.easing, c.p0 != 0, c.c1, c.p1, c.p2, c.p3, c.q0, c.q1};
      return c.v0 + elastic_offset_q8(e, s);
    }
    default: return c.v0 + mul_q30(c.c1, ease_fraction_q30(c.kind, c.easing, s, c.p0));
#else
    default: return c.v0;  // not reached: check_image refuses the families this build left out
#endif
  }
}

// |a - b| as an unsigned word, exactly (32-bit arithmetic: a small core's 64-bit compares are
// library calls).
uint32_t distance(int32_t a, int32_t b) {
  return a >= b ? static_cast<uint32_t>(a) - static_cast<uint32_t>(b) : static_cast<uint32_t>(b) - static_cast<uint32_t>(a);
}

int32_t snapped_to_ends(const Channel& ch, int32_t t) {
  if (distance(t, ch.start) <= ch.snap_ticks) return ch.start;
  if (distance(t, ch.end) <= ch.snap_ticks) return ch.end;
  return t;
}

#if AVAR_DEVICE_EXTRAPOLATION
const int64_t kHuge = static_cast<int64_t>(1) << 40;  // Q8 far beyond any output

// value + slope (Q8 per second) * ticks / ticks_per_second, saturated far beyond the output.
int64_t extrapolated(int64_t value, int64_t slope, int64_t ticks, uint32_t ticks_per_second) {
  if (slope == 0 || ticks == 0) return value;
  const bool negative = (slope < 0) != (ticks < 0);
  const uint64_t s = static_cast<uint64_t>(slope < 0 ? -slope : slope), n = static_cast<uint64_t>(ticks < 0 ? -ticks : ticks);
  const uint64_t whole = n / ticks_per_second, rest = n % ticks_per_second;
  if (whole != 0 && s > static_cast<uint64_t>(kHuge) / whole) return negative ? -kHuge : kHuge;
  uint64_t change = s * whole + s * rest / ticks_per_second;
  if (change > static_cast<uint64_t>(kHuge)) change = static_cast<uint64_t>(kHuge);
  return value + (negative ? -static_cast<int64_t>(change) : static_cast<int64_t>(change));
}

#endif

int64_t extrapolate(const Channel& ch, int32_t t) {
  const bool before = !(t > ch.start);
  const int64_t value = static_cast<int64_t>(before ? ch.first_value : ch.last_value) * 256;
#if AVAR_DEVICE_EXTRAPOLATION
  if (ch.flags & kChannelLinearExtrapolation)
    return extrapolated(value, before ? ch.slope_before : ch.slope_after, static_cast<int64_t>(t) - (before ? ch.start : ch.end),
                        ch.ticks_per_second);
#endif
  return value;
}

// Moves the cache to the segment holding t (start < t < end).
void find_segment(const Channel& ch, SegmentCache& c, int32_t t) {
  if (c.index == kNoSegment || t < c.t0) load_segment(ch, c, ch.keys_at, 0, 0, 0);
  while (t >= c.t1) load_segment(ch, c, c.next_at, static_cast<uint16_t>(c.index + 1), c.t0, c.k0);
}

// t in the cached segment (found for t), or the key it is within the snap of (the nearer, should
// both be; the next key moves the cache to its segment).
int32_t snapped_in_segment(const Channel& ch, SegmentCache& c, int32_t t) {
  const uint32_t after_start = static_cast<uint32_t>(t) - static_cast<uint32_t>(c.t0),
                 before_end = static_cast<uint32_t>(c.t1) - static_cast<uint32_t>(t);
  if (before_end <= ch.snap_ticks && before_end < after_start) {
    find_segment(ch, c, c.t1);
    return c.t0;
  }
  return after_start <= ch.snap_ticks ? c.t0 : t;
}

int64_t evaluate_keys(const Channel& ch, SegmentCache& c, int32_t t) {
  t = snapped_to_ends(ch, t);
  if (!(t > ch.start) || t >= ch.end) return extrapolate(ch, t);
  find_segment(ch, c, t);
  return evaluate_in(c, snapped_in_segment(ch, c, t));
}

#if AVAR_DEVICE_FAST
// The fast path of a sample, in 32-bit words only: a channel without Cycles or linear
// extrapolation, at a tick outside its keys or in a step, linear or narrow cubic or Bezier
// segment. False where the general path is needed; the value is the general path's, bit for bit.
bool sample_narrow(const Channel& ch, SegmentCache& c, int32_t tick, int32_t& q8) {
  if (ch.flags != 0) return false;
  const int32_t t = snapped_to_ends(ch, tick);
  if (!(t > ch.start) || t >= ch.end) {
    q8 = (t > ch.start ? ch.last_value : ch.first_value) * 256;  // constant extrapolation
    return true;
  }
  find_segment(ch, c, t);
  const int32_t at = snapped_in_segment(ch, c, t);
  switch (c.kind) {
    case kStep: q8 = static_cast<int32_t>(c.v0); return true;
    case kLinear: q8 = static_cast<int32_t>(c.v0) + mul_q30_narrow(static_cast<int32_t>(c.c1), segment_time(c, at)); return true;
    case kCubic:
    case kBezier: {
      if (!c.narrow) return false;
      const uint32_t s = segment_time(c, at);
      const uint32_t x = c.kind == kBezier ? static_cast<uint32_t>(bezier_parameter(c, s)) : s;
      const int32_t inner = static_cast<int32_t>(c.c2) + mul_q30_narrow(static_cast<int32_t>(c.c3), x);
      const int32_t middle = static_cast<int32_t>(c.c1) + mul_q30_narrow(inner, x);
      q8 = static_cast<int32_t>(c.v0) + mul_q30_narrow(middle, x);
      return true;
    }
    default: return false;
  }
}
#endif

#if AVAR_DEVICE_CYCLES
// Blender's Cycles time map in integer ticks (avar's Curve::cycle_time, exact here): t outside
// the keys mapped into them, with the value offset of repeat_offset. Returns false past the count.
bool cycle_time(const Channel& ch, int32_t t, int32_t& mapped, int64_t& offset) {
  offset = 0;
  int side = 0;
  uint8_t mode = kCycleNone;
  uint32_t count = 0;
  if (t < ch.start && ch.cycle_before != kCycleNone) {
    side = -1, mode = ch.cycle_before, count = ch.before_count;
  } else if (t > ch.end && ch.cycle_after != kCycleNone) {
    side = 1, mode = ch.cycle_after, count = ch.after_count;
  }
  const int64_t dx = static_cast<int64_t>(ch.end) - ch.start;
  if (side == 0 || dx == 0) {
    mapped = t;
    return true;
  }
  const int64_t d = side > 0 ? static_cast<int64_t>(t) - ch.end : static_cast<int64_t>(ch.start) - t;  // > 0
  const int64_t k = d / dx, w = d % dx;
  if (count != 0 && (w == 0 ? k > count : k >= count)) return false;
  if (mode == kCycleRepeatOffset) offset = side * (w == 0 ? k : k + 1) * ch.cycle_offset;
  if (w == 0) {
    const bool flipped = mode == kCycleMirror && (k % 2) == 1;
    mapped = (side > 0) != flipped ? ch.end : ch.start;
  } else if (mode == kCycleMirror && (k % 2) == 0) {
    mapped = static_cast<int32_t>(side < 0 ? ch.start + w : ch.end - w);
  } else {
    mapped = static_cast<int32_t>(side > 0 ? ch.start + w : ch.end - w);
  }
  return true;
}
#endif

}  // namespace

bool open_channel(const uint8_t* image, uint32_t size, uint8_t index, Channel& ch) {
  ShowHeader header;
  if (check_image(image, size, header) != kImageOk || index >= header.channel_count) return false;
  ByteReader r = {image, size, channel_offset(image, index), false};
  ch.image = image;
  ch.size = size;
  ch.ticks_per_second = header.ticks_per_second;
  ch.snap_ticks = header.snap_ticks;
  ch.flags = r.u8();
  ch.key_count = static_cast<uint16_t>(r.fixed(2));
  // (check_image refused the features this build left out)
#if AVAR_DEVICE_EXTRAPOLATION
  ch.slope_before = ch.slope_after = 0;
  if (ch.flags & kChannelLinearExtrapolation) {
    ch.slope_before = r.zigzag();
    ch.slope_after = r.zigzag();
  }
#endif
#if AVAR_DEVICE_CYCLES
  ch.cycle_before = ch.cycle_after = kCycleNone;
  ch.before_count = ch.after_count = 0;
  ch.cycle_offset = 0;
  if (ch.flags & kChannelCycles) {
    const uint8_t modes = r.u8();
    ch.cycle_before = modes & 0x0fu;
    ch.cycle_after = modes >> 4;
    ch.before_count = static_cast<uint32_t>(r.varint());
    ch.after_count = static_cast<uint32_t>(r.varint());
    ch.cycle_offset = r.zigzag();
  }
#endif
  ch.keys_at = r.at;
  // The first and last keys: the last by walking the keys once.
  int32_t time = 0, value = 0;
  for (uint16_t i = 0; i < ch.key_count; ++i) {
    const KeyHead k = read_head(r, i == 0, time, value);
    time = k.time, value = k.value;
    if (i == 0) ch.start = time, ch.first_value = value;
    switch (k.header & 0x1fu) {
      case kCubic: r.zigzag(), r.zigzag(); break;
      case kBezier: {
        const unsigned bytes = k.header & kKeyWideBezier ? 3 : 2;
        r.zigzag(), r.zigzag();
        if (!(k.header & kKeySameHandleTimes)) r.fixed(bytes), r.fixed(bytes);
        break;
      }
      case kBack: r.zigzag(); break;
      case kElastic: r.u8(), r.zigzag(), r.varint(), r.zigzag(); break;
      default: break;
    }
  }
  ch.end = time;
  ch.last_value = value;
  return !r.overrun;
}

void reset_cache(SegmentCache& cache) {
  cache.index = kNoSegment;
  cache.t0 = cache.t1 = 0;
}

int64_t sample_q8(const Channel& ch, SegmentCache& cache, int32_t tick) {
#if AVAR_DEVICE_FAST
  int32_t narrow = 0;
  if (sample_narrow(ch, cache, tick, narrow)) return narrow;
#endif
#if AVAR_DEVICE_CYCLES
  if (!(ch.flags & kChannelCycles)) return evaluate_keys(ch, cache, tick);
  const int32_t t = snapped_to_ends(ch, tick);  // before the cycle map: the end key, not the next cycle
  if (t >= ch.start && t <= ch.end) return evaluate_keys(ch, cache, t);
  int32_t mapped = t;
  int64_t offset = 0;
  if (!cycle_time(ch, t, mapped, offset)) return evaluate_keys(ch, cache, t);
  return evaluate_keys(ch, cache, mapped) + offset;
#else
  return evaluate_keys(ch, cache, tick);
#endif
}

uint16_t sample(const Channel& ch, SegmentCache& cache, int32_t tick) {
  // Rounded to the nearest unit and saturated: below 0 is 0; a shift by a whole byte otherwise.
#if AVAR_DEVICE_FAST
  int32_t narrow = 0;
  if (sample_narrow(ch, cache, tick, narrow)) {
    const int32_t rounded = narrow + 128;  // |narrow| < 2^31 - 2^8: the narrow path's bound
    if (rounded < 0) return 0;
    const uint32_t units = static_cast<uint32_t>(rounded) >> 8;
    return units > 65535u ? static_cast<uint16_t>(65535u) : static_cast<uint16_t>(units);
  }
#endif
  const int64_t q8 = sample_q8(ch, cache, tick) + 128;
  if (q8 < 0) return 0;
  const uint64_t units = static_cast<uint64_t>(q8) >> 8;
  return units > 65535u ? static_cast<uint16_t>(65535u) : static_cast<uint16_t>(units);
}

}  // namespace device
}  // namespace avar
