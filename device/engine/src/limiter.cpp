#include "avar/device/limiter.hpp"

#include "avar/device/fixed_math.hpp"

namespace avar {
namespace device {

int64_t stopping_distance(int64_t speed, int64_t accel) {
  if (speed <= 0 || accel <= 0) return 0;
  const uint64_t v = static_cast<uint64_t>(speed), a = static_cast<uint64_t>(accel);
  const uint64_t n = (v + a - 1) / a;
  return static_cast<int64_t>(n * v - a * n * (n - 1) / 2);
}

void limiter_prepare(ChannelLimits& limits) { limits.reach = stopping_distance(limits.speed, limits.accel); }

bool limits_usable(const ChannelLimits& l) {
  return l.low <= l.rest && l.rest <= l.high && l.speed > 0 && l.accel > 0 && l.reach == stopping_distance(l.speed, l.accel);
}

ChannelLimits read_limits(const uint8_t* stored) {
  int64_t fields[6];
  const uint8_t* at = stored;
  for (uint8_t f = 0; f < 6; ++f) {
    uint64_t v = 0;
    for (uint8_t b = 0; b < 8; ++b) v |= static_cast<uint64_t>(AVAR_DEVICE_READ_BYTE(at++)) << (8 * b);
    fields[f] = static_cast<int64_t>(v);
  }
  ChannelLimits l = {fields[0], fields[1], fields[2], fields[3], fields[4], fields[5]};
  return l;
}

void write_limits(const ChannelLimits& limits, uint8_t* out) {
  const int64_t fields[6] = {limits.low, limits.high, limits.rest, limits.speed, limits.accel, limits.reach};
  for (uint8_t f = 0; f < 6; ++f)
    for (uint8_t b = 0; b < 8; ++b) *out++ = static_cast<uint8_t>(static_cast<uint64_t>(fields[f]) >> (8 * b));
}

LimiterState limiter_at_rest(const ChannelLimits& limits) {
  const int64_t rest = clamp64(limits.rest, limits.low, limits.high);
  LimiterState s = {rest, 0, rest, false};
  return s;
}

int64_t braking_speed(int64_t distance, int64_t accel) {
  if (distance <= 0) return 0;
  // Moving by v, then v - a, v - 2a, ... while positive: n = ceil(v / a) steps cover
  // S(v) = n v - a n (n - 1) / 2. S grows with v; for each n the largest v of that many steps is
  // min(n a, (d + a n (n - 1) / 2) / n), valid when above (n - 1) a. The continuous estimate
  // n ~ sqrt(2 d / a) puts the answer's n within two of n0. Positions are below 2^33 (Q16 of 16
  // bits): nothing here overflows.
  const uint64_t a = static_cast<uint64_t>(accel), d = static_cast<uint64_t>(distance);
  if (a >= d) return distance;  // one step, then a stop
  const uint64_t n0 = isqrt64(2 * d / a) + 1;
  int64_t best = 0;
  for (uint64_t n = n0 > 2 ? n0 - 2 : 1; n <= n0 + 2; ++n) {
    const uint64_t most = n * a, fits = (d + a * n * (n - 1) / 2) / n;
    const uint64_t v = most < fits ? most : fits;
    if (v > (n - 1) * a && static_cast<int64_t>(v) > best) best = static_cast<int64_t>(v);
  }
  return best;
}

void limiter_step(const ChannelLimits& l, LimiterState& s, int64_t target) {
  target = clamp64(target, l.low, l.high);
  // The target's own motion this tick (a jump larger than the speed is not motion).
  int64_t moving = s.tracking ? target - s.target : 0;
  if (moving > l.speed || moving < -l.speed) moving = 0;
  s.target = target;
  s.tracking = true;
  // With the target's motion, and toward where it was: slow enough to stop on it (and to land
  // on it); caught up, the position moves with the target exactly.
  const int64_t distance = target - moving - s.position;
  const int64_t magnitude = distance < 0 ? -distance : distance;
  // The closing speed, relative to the target: at most the speed, the braking speed (beyond the
  // stop from full speed that is the speed itself: not computed) and the distance.
  int64_t closing = magnitude > l.reach ? l.speed : braking_speed(magnitude, l.accel);
  if (closing > l.speed) closing = l.speed;
  if (closing > magnitude) closing = magnitude;
  const int64_t wanted = clamp64(moving + (distance < 0 ? -closing : closing), -l.speed, l.speed);
  // The speed changes by at most the acceleration.
  int64_t v = clamp64(wanted, s.velocity - l.accel, s.velocity + l.accel);
  // The range's ends are kept by braking in time; with the state within the limits this never
  // needs more than the acceleration (the stop from the present speed always fits), so it only
  // guards against a state that did not come from these limits.
  const int64_t to_low = s.position - l.low, to_high = l.high - s.position;
  v = clamp64(v, to_low > l.reach ? -l.speed : -braking_speed(to_low, l.accel),
              to_high > l.reach ? l.speed : braking_speed(to_high, l.accel));
  v = clamp64(v, -l.speed, l.speed);
  s.velocity = v;
  s.position = clamp64(s.position + v, l.low, l.high);
}

uint16_t limiter_output(const LimiterState& state) {
  return static_cast<uint16_t>(clamp64(shift_floor(state.position + 32768, 16), 0, 65535));
}

}  // namespace device
}  // namespace avar
