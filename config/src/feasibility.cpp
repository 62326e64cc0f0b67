#include "avar/config/feasibility.hpp"


#include <algorithm>
#include <cmath>

#include "avar/core/format.hpp"

namespace avar::config {
namespace {

constexpr int kSamples = 400;  // per segment, for the speed and acceleration measurements

struct Demand {
  double speed = 0;
  double acceleration = 0;
  double low = 0, high = 0;
};

/// Largest |first| and |second| finite differences of the curve inside one segment.
Demand measure(const playback::Curve& curve, double t0, double t1) {
  const double h = (t1 - t0) / kSamples;
  Demand d;
  double prev = curve.evaluate(t0), prev_speed = 0;
  d.low = d.high = prev;
  for (int i = 1; i <= kSamples; ++i) {
    // Stay just inside the segment at its end: the next key may jump (step).
    const double t = i == kSamples ? t1 - 1e-9 * (t1 - t0) : t0 + i * h;
    const double v = curve.evaluate(t);
    const double speed = (v - prev) / (t - (t0 + (i - 1) * h));
    d.speed = std::max(d.speed, std::abs(speed));
    if (i > 1) d.acceleration = std::max(d.acceleration, std::abs(speed - prev_speed) / h);
    d.low = std::min(d.low, v);
    d.high = std::max(d.high, v);
    prev = v;
    prev_speed = speed;
  }
  return d;
}

/// The factor by which a segment must be slowed: speed scales with 1/f, acceleration with 1/f².
double stretch_needed(const Demand& d, const control::ChannelSpec& c) {
  return std::max({1.0, d.speed / c.max_velocity, std::sqrt(d.acceleration / c.max_acceleration)});
}

/// A piecewise-linear map of show time: slope `factor` inside each stretched span, 1 elsewhere.
struct TimeWarp {
  struct Span {
    double t0, t1, factor;
  };
  std::vector<Span> spans;  // disjoint, sorted

  double operator()(double t) const {
    double added = 0;
    for (const Span& s : spans) {
      if (t <= s.t0) break;
      added += (std::min(t, s.t1) - s.t0) * (s.factor - 1);
    }
    return t + added;
  }
};

TimeWarp warp_for(std::vector<TimeWarp::Span> spans) {
  std::sort(spans.begin(), spans.end(), [](const auto& a, const auto& b) { return a.t0 < b.t0; });
  TimeWarp warp;
  for (const auto& s : spans) {
    if (!warp.spans.empty() && s.t0 < warp.spans.back().t1) {
      // Overlapping spans: one span, slowed by the larger factor (never too little).
      warp.spans.back().t1 = std::max(warp.spans.back().t1, s.t1);
      warp.spans.back().factor = std::max(warp.spans.back().factor, s.factor);
    } else {
      warp.spans.push_back(s);
    }
  }
  return warp;
}

}  // namespace

std::string Infeasible::to_string() const {
  const std::string u = unit.empty() ? "" : " " + unit;
  std::string what;
  switch (kind) {
    case Kind::speed: what = "speed " + format_number(required) + u + "/s, allowed " + format_number(allowed) + u + "/s"; break;
    case Kind::acceleration:
      what = "acceleration " + format_number(required) + u + "/s², allowed " + format_number(allowed) + u + "/s²";
      break;
    case Kind::range: what = "reaches " + format_number(required) + u + ", limit " + format_number(allowed) + u; break;
    case Kind::jump: what = "jumps by " + format_number(required) + u + " at once (step); the limiter shapes it"; break;
  }
  return avar::to_string(where) + ": " + channel + " " + format_number(t0) + "-" + format_number(t1) + " s: " + what;
}

std::vector<Infeasible> check_feasibility(const playback::Show& show, const control::Rig& rig) {
  std::vector<Infeasible> found;
  for (const playback::Track& track : show.tracks) {
    const auto ci = rig.find_channel(track.channel);
    if (!ci) continue;
    const control::ChannelSpec& c = rig.channels[*ci];
    const auto& keys = track.raw.keys;
    for (std::size_t k = 0; k + 1 < keys.size(); ++k) {
      const double t0 = keys[k].time, t1 = keys[k + 1].time;
      const Infeasible base{Infeasible::Kind::speed, c.name, c.unit, t0, t1, 0, 0, keys[k].where};
      if (keys[k].interpolation == playback::Interpolation::step) {
        const double jump = std::abs(keys[k + 1].value - keys[k].value);
        if (jump > 0) {
          Infeasible f = base;
          f.kind = Infeasible::Kind::jump;
          f.required = jump;
          found.push_back(f);
        }
        continue;
      }
      const Demand d = measure(track.curve, t0, t1);
      if (d.speed > c.max_velocity * (1 + 1e-9)) {
        Infeasible f = base;
        f.required = d.speed, f.allowed = c.max_velocity;
        found.push_back(f);
      }
      if (d.acceleration > c.max_acceleration * (1 + 1e-9)) {
        Infeasible f = base;
        f.kind = Infeasible::Kind::acceleration;
        f.required = d.acceleration, f.allowed = c.max_acceleration;
        found.push_back(f);
      }
      if (d.low < c.min || d.high > c.max) {
        Infeasible f = base;
        f.kind = Infeasible::Kind::range;
        f.required = d.high > c.max ? d.high : d.low;
        f.allowed = d.high > c.max ? c.max : c.min;
        found.push_back(f);
      }
    }
  }
  return found;
}

playback::Show retime(const playback::Show& show, const control::Rig& rig) {
  playback::Show out = show;
  // Stretching one span can change the demand of a segment that crosses its edge, so repeat
  // until nothing needs more time (a few rounds at most in practice).
  for (int round = 0; round < 8; ++round) {
    std::vector<TimeWarp::Span> spans;
    for (const playback::Track& track : out.tracks) {
      const auto ci = rig.find_channel(track.channel);
      if (!ci) continue;
      const auto& keys = track.raw.keys;
      for (std::size_t k = 0; k + 1 < keys.size(); ++k) {
        if (keys[k].interpolation == playback::Interpolation::step) continue;
        const double f = stretch_needed(measure(track.curve, keys[k].time, keys[k + 1].time), rig.channels[*ci]);
        // A little more than just enough, so that the measurement's own rounding cannot leave a
        // segment a hair over the limit.
        if (f > 1 + 1e-9) spans.push_back({keys[k].time, keys[k + 1].time, f * (1 + 1e-6)});
      }
    }
    if (spans.empty()) break;
    const TimeWarp warp = warp_for(spans);
    for (playback::Track& track : out.tracks) {
      for (playback::RawKey& key : track.raw.keys) {
        // Handles move with the time around them, so a stretched segment keeps its shape.
        key.time = warp(key.time);
        if (key.left) key.left->time = warp(key.left->time);
        if (key.right) key.right->time = warp(key.right->time);
      }
      track.curve = playback::Curve::build(track.raw);
    }
    out.duration = warp(out.duration);
  }
  return out;
}

}  // namespace avar::config
