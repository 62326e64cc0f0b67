#include "avar/playback/runtime/blink_generator.hpp"

#include <algorithm>
#include <cmath>

#include "avar/playback/runtime/min_jerk.hpp"

namespace avar::playback {
namespace {
constexpr double kBlinkLimitShare = 0.9;
}  // namespace

BlinkGenerator::BlinkGenerator(const BlinkSpec& spec, std::span<const IdleChannelLimits> limits, std::uint64_t seed)
    : spec_(spec), random_(seed), close_s_(spec.close_s), open_s_(spec.open_s) {
  for (const BlinkLid& lid : spec_.lids) {
    const double travel = lid.closed - lid.open;
    close_s_ = min_jerk_duration(travel, limits[lid.channel], kBlinkLimitShare, close_s_);
    open_s_ = min_jerk_duration(travel, limits[lid.channel], kBlinkLimitShare, open_s_);
  }
  // The first event comes within the first interval, not at once.
  event_start_ = random_.uniform(0.0, spec_.interval_max);
  event_double_ = random_.chance(spec_.double_probability);
}

void BlinkGenerator::schedule_after(double start) noexcept {
  event_start_ = start + random_.uniform(spec_.interval_min, spec_.interval_max);
  event_double_ = random_.chance(spec_.double_probability);
}

double BlinkGenerator::one_blink(double s) const noexcept {
  if (s < 0) return 0;
  if (s < close_s_) return min_jerk(s / close_s_);
  s -= close_s_;
  if (s < spec_.hold_s) return 1;
  s -= spec_.hold_s;
  if (s < open_s_) return 1 - min_jerk(s / open_s_);
  return 0;
}

double BlinkGenerator::closure(double t) noexcept {
  const double second = blink_s() + spec_.double_gap_s;
  for (;;) {
    const double event_end = event_start_ + (event_double_ ? second + blink_s() : blink_s());
    if (t < event_end) break;
    schedule_after(event_start_);
    // An event never starts before the last one ended (the interval is at least one event long
    // once validated; a very short interval simply waits).
    event_start_ = std::max(event_start_, event_end);
  }
  const double since = t - event_start_;
  double c = one_blink(since);
  if (event_double_) c = std::max(c, one_blink(since - second));
  return c;
}

void BlinkGenerator::sample(double t, std::span<double> frame) noexcept {
  const double c = closure(t);
  for (const BlinkLid& lid : spec_.lids) frame[lid.channel] = lid.open + c * (lid.closed - lid.open);
}

}  // namespace avar::playback
