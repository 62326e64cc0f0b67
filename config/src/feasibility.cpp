#include "avar/config/feasibility.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "avar/core/format.hpp"
#include "avar/config/show_behaviour.hpp"
#include "avar/playback/runtime/curve.hpp"
#include "avar/playback/runtime/sampler.hpp"
#include "played_span.hpp"

namespace avar::config {
namespace {

constexpr int kSamples = 400;             // per segment, for the speed and acceleration measurements
constexpr double kBehaviourPiece = 0.25;  // s: behaviour layers are measured in pieces this long
// s: a time this far from a key is not that key's time for the curves (Curve::kKeySnap): the
// probes that look just before a key, or either side of a breakpoint, stand this far off.
constexpr double kInsideKey = 2 * playback::Curve::kKeySnap;

struct Demand {
  double speed = 0;
  double acceleration = 0;
  double low = 0, high = 0;
};

/// Largest |first| and |second| finite differences, and the extremes, of each of the `n` values
/// that `fill(t, values)` writes, inside one segment [t0, t1].
template <typename Fill>
std::vector<Demand> measure_values(std::size_t n, Fill fill, double t0, double t1) {
  const double h = (t1 - t0) / kSamples;
  std::vector<Demand> d(n);
  std::vector<double> prev(n), prev_speed(n, 0), v(n);
  fill(t0, prev);
  for (std::size_t c = 0; c < n; ++c) d[c].low = d[c].high = prev[c];
  for (int i = 1; i <= kSamples; ++i) {
    // Stay just inside the segment at its end, where the next key may jump (step): further in
    // than the curves' key snap, within which the time is the next key's.
    const double t = i == kSamples ? t1 - std::min(0.5 * h, std::max(1e-9 * (t1 - t0), kInsideKey)) : t0 + i * h;
    fill(t, v);
    for (std::size_t c = 0; c < n; ++c) {
      const double speed = (v[c] - prev[c]) / (t - (t0 + (i - 1) * h));
      d[c].speed = std::max(d[c].speed, std::abs(speed));
      if (i > 1) d[c].acceleration = std::max(d[c].acceleration, std::abs(speed - prev_speed[c]) / h);
      d[c].low = std::min(d[c].low, v[c]);
      d[c].high = std::max(d[c].high, v[c]);
      prev[c] = v[c];
      prev_speed[c] = speed;
    }
  }
  return d;
}

Demand measure(const playback::Curve& curve, double t0, double t1) {
  return measure_values(
      1, [&](double t, std::vector<double>& v) { v[0] = curve.evaluate(t); }, t0, t1)[0];
}

/// The findings of one segment's demand against its channel's limits.
void report(const Demand& d, const Infeasible& base, const rig::ChannelSpec& c, std::vector<Infeasible>& found) {
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

/// Show times where the composed motion of a layered show may have a corner or a jump: the
/// show's key times, every placement's start, end and fade edges, and the show times at which a
/// placement reaches one of its clip's key times (or its ends), through its time warp and mode.
std::vector<double> composed_breakpoints(const playback::Show& show) {
  std::vector<double> b{0, show.duration};
  for (const playback::Track& track : show.tracks)
    for (const playback::RawKey& key : track.raw.keys) b.push_back(key.time);
  for (const playback::Layer& layer : show.layers) {
    if (const auto& behaviour = layer.behaviour) {
      // Generated motion has no keys: its span and fade edges, and a cut every
      // kBehaviourPiece so that each piece is measured finely (saccades last tens of ms).
      const playback::LayerBehaviour& g = *behaviour;
      b.insert(b.end(), {g.from, g.to, g.from + g.fade_in, g.to - g.fade_out});
      for (double t = g.from + kBehaviourPiece; t < g.to; t += kBehaviourPiece) b.push_back(t);
    }
    for (const playback::Placement& p : layer.placements) {
      const playback::Clip& clip = show.clips[p.clip];
      b.insert(b.end(), {p.start, p.end, p.start + p.fade_in, p.end - p.fade_out});
      std::vector<double> keys{0, clip.duration};
      for (const playback::Track& track : clip.tracks)
        for (const playback::RawKey& key : track.raw.keys) keys.push_back(key.time);
      const double d = clip.duration;
      const double u0 = p.offset, u1 = p.offset + (p.end - p.start) * p.speed;  // clip seconds played
      const auto at = [&](double u) {
        if (u >= u0 && u <= u1) b.push_back(p.start + (u - u0) / p.speed);
      };
      for (double key : keys) {
        const double k = p.reverse ? d - key : key;  // where the played time meets the key
        if (clip.mode == playback::ClipMode::hold) {
          at(k);
          continue;
        }
        const double period = clip.mode == playback::ClipMode::loop ? d : 2 * d;
        for (double n = std::floor((u0 - 2 * d) / period); n * period <= u1 + 2 * d; ++n) {
          at(k + n * period);
          if (clip.mode == playback::ClipMode::ping_pong) at(2 * d - k + n * period);
        }
      }
    }
  }
  std::sort(b.begin(), b.end());
  std::vector<double> unique;
  for (double t : b)
    if (t >= 0 && t <= show.duration && (unique.empty() || t - unique.back() > 1e-9 * show.duration)) unique.push_back(t);
  return unique;
}

/// Where to point for a channel's composed motion at show time t: the top placement that moves
/// it then, else the show's own track, else the show.
SourceLocation composed_source(const playback::Show& show, const std::string& channel, double t) {
  for (auto layer = show.layers.rbegin(); layer != show.layers.rend(); ++layer) {
    if (!layer->touches(channel)) continue;
    if (layer->behaviour && layer->behaviour->weight(t) > 0) {
      const std::vector<std::string> moved = playback::behaviour_channels(*layer);
      if (std::find(moved.begin(), moved.end(), channel) != moved.end()) return layer->behaviour->where;
    }
    for (const playback::Placement& p : layer->placements)
      if (p.weight(t) > 0)
        for (const playback::Track& track : show.clips[p.clip].tracks)
          if (track.channel == channel) return p.where;
  }
  for (const playback::Track& track : show.tracks)
    if (track.channel == channel) return track.where;
  return show.where;
}

/// Adds a finding, or extends the same finding of the piece just before.
void add_merged(const Infeasible& f, std::vector<Infeasible>& found) {
  for (std::size_t back = 0; back < std::min<std::size_t>(found.size(), 16); ++back) {
    Infeasible& g = found[found.size() - 1 - back];
    if (g.kind == f.kind && g.channel == f.channel && g.t1 == f.t0 && to_string(g.where) == to_string(f.where)) {
      g.t1 = f.t1;
      g.required = f.kind == Infeasible::Kind::range && f.required < f.allowed ? std::min(g.required, f.required)
                                                                               : std::max(g.required, f.required);
      return;
    }
  }
  found.push_back(f);
}

/// A layered show is checked on its composed motion, as the sampler plays it on this rig: between
/// consecutive breakpoints (composed_breakpoints) the motion is smooth and is measured as a
/// segment is; at a breakpoint a jump (a cut without a fade, a step key) is listed as a jump.
std::vector<Infeasible> check_composed_feasibility(const playback::Show& given, const rig::Rig& rig) {
  // Behaviour layers play on this rig's channels and limits.
  std::optional<playback::Show> bound;
  if (has_unbound_behaviour(given)) {
    try {
      bind_show_behaviour(bound.emplace(given), rig);
    } catch (const InputError&) {
      return {};  // check_show_against_rig reports it
    }
  }
  const playback::Show& show = bound ? *bound : given;
  std::vector<std::string> names;
  for (const rig::ChannelSpec& c : rig.channels) names.push_back(c.name);
  const std::vector<double> rest = rig.rest_frame();
  std::optional<playback::Sampler> sampler;
  try {
    sampler.emplace(show, names, rest);
  } catch (const std::invalid_argument&) {
    return {};  // a channel the rig does not have: check_show_against_rig reports it
  }
  const std::size_t n = names.size();
  const auto fill = [&](double t, std::vector<double>& frame) { sampler->sample(t, frame); };
  const std::vector<double> b = composed_breakpoints(show);
  std::vector<Infeasible> found;
  std::vector<double> before(n), after(n);
  for (std::size_t i = 1; i + 1 < b.size(); ++i) {
    constexpr double kJumpProbe = kInsideKey;  // seconds either side of a breakpoint
    fill(b[i] - kJumpProbe, before);
    fill(b[i] + kJumpProbe, after);
    for (std::size_t c = 0; c < n; ++c) {
      if (rig.channels[c].digital()) continue;  // switches: its jumps are what it is for
      const double jump = std::abs(after[c] - before[c]);
      // Ten times what the channel could move at its top speed across the probe is no smooth motion.
      if (jump > 20 * kJumpProbe * rig.channels[c].max_velocity)
        found.push_back({Infeasible::Kind::jump, names[c], rig.channels[c].unit, b[i], b[i], jump, 0,
                         composed_source(show, names[c], b[i] + kJumpProbe)});
    }
  }
  for (std::size_t i = 0; i + 1 < b.size(); ++i) {
    const double t0 = b[i], t1 = b[i + 1];
    const std::vector<Demand> demand = measure_values(n, fill, t0 + 1e-9 * (t1 - t0), t1);
    for (std::size_t c = 0; c < n; ++c) {
      if (rig.channels[c].digital()) continue;
      std::vector<Infeasible> piece;
      const Infeasible base{Infeasible::Kind::speed,
                            names[c],
                            rig.channels[c].unit,
                            t0,
                            t1,
                            0,
                            0,
                            composed_source(show, names[c], 0.5 * (t0 + t1))};
      report(demand[c], base, rig.channels[c], piece);
      for (const Infeasible& f : piece) add_merged(f, found);
    }
  }
  return found;
}

/// The factor by which a segment must be slowed: speed scales with 1/f, acceleration with 1/f².
double stretch_needed(const Demand& d, const rig::ChannelSpec& c) {
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

double SegmentDemand::usage() const {
  const double outside = std::max({0.0, min - low, high - max});
  const double reach = outside > 0 ? 1 + outside / std::max(max - min, 1e-12) : 0.0;
  return std::max(
      {max_velocity > 0 ? speed / max_velocity : 0.0, max_acceleration > 0 ? acceleration / max_acceleration : 0.0, reach});
}

std::string SegmentDemand::to_string() const {
  const std::string u = unit.empty() ? "" : " " + unit;
  const auto percent = [](double share) { return format_number(std::round(share * 1000) / 10) + " %"; };
  std::string text = avar::to_string(where) + ": " + channel + " " + format_number(t0) + "-" + format_number(t1) + " s: speed " +
                     percent(speed / max_velocity) + " of " + format_number(max_velocity) + u + "/s, acceleration " +
                     percent(acceleration / max_acceleration) + " of " + format_number(max_acceleration) + u + "/s²";
  if (low < min || high > max)
    text += ", reaches " + format_number(high > max ? high : low) + u + " outside [" + format_number(min) + ", " +
            format_number(max) + "]";
  return text;
}

std::vector<SegmentDemand> segment_demands(const playback::Show& show, const rig::Rig& rig) {
  std::vector<SegmentDemand> found;
  if (show.layered()) return found;
  for (const playback::Track& track : show.tracks) {
    const auto ci = rig.find_channel(track.channel);
    if (!ci || rig.channels[*ci].digital()) continue;
    const rig::ChannelSpec& c = rig.channels[*ci];
    const auto& keys = track.raw.keys;
    for (std::size_t k = 0; k + 1 < keys.size(); ++k) {
      if (keys[k].interpolation == playback::Interpolation::step) continue;
      const auto span = detail::played_part(keys[k].time, keys[k + 1].time, show.duration);
      if (!span) continue;
      const Demand d = measure(track.curve, span->t0, span->t1);
      found.push_back({c.name, c.unit, span->t0, span->t1, d.speed, d.acceleration, d.low, d.high, c.max_velocity,
                       c.max_acceleration, c.min, c.max, keys[k].where});
    }
  }
  return found;
}

std::vector<Infeasible> check_feasibility(const playback::Show& show, const rig::Rig& rig) {
  if (show.layered()) return check_composed_feasibility(show, rig);
  std::vector<Infeasible> found;
  for (const playback::Track& track : show.tracks) {
    const auto ci = rig.find_channel(track.channel);
    if (!ci) continue;
    const rig::ChannelSpec& c = rig.channels[*ci];
    // A digital channel switches at once: no speed, acceleration or jump to check.
    if (c.digital()) continue;
    const auto& keys = track.raw.keys;
    for (std::size_t k = 0; k + 1 < keys.size(); ++k) {
      // Only what plays: a segment before 0 or after the end shapes the curve, it never moves.
      const auto span = detail::played_part(keys[k].time, keys[k + 1].time, show.duration);
      if (!span) continue;
      const double t0 = span->t0, t1 = span->t1;
      const Infeasible base{Infeasible::Kind::speed, c.name, c.unit, t0, t1, 0, 0, keys[k].where};
      if (keys[k].interpolation == playback::Interpolation::step) {
        // The step is taken at the next key: in the show only if that key plays.
        const double jump = std::abs(keys[k + 1].value - keys[k].value);
        if (jump > 0 && keys[k + 1].time <= show.duration) {
          Infeasible f = base;
          f.kind = Infeasible::Kind::jump;
          f.required = jump;
          found.push_back(f);
        }
        continue;
      }
      report(measure(track.curve, t0, t1), base, c, found);
    }
  }
  return found;
}

playback::Show retime(const playback::Show& show, const rig::Rig& rig) {
  if (show.layered())
    throw InputError(show.where,
                     "show '" + show.name +
                         "' has layers of clips, which retiming cannot stretch honestly (a stretch would "
                         "change where clips overlap and fade); expected a show without layers (slow a placement with its "
                         "speed instead)");
  playback::Show out = show;
  // Stretching one span can change the demand of a segment that crosses its edge, so repeat
  // until nothing needs more time (a few rounds at most in practice).
  for (int round = 0; round < 8; ++round) {
    std::vector<TimeWarp::Span> spans;
    for (const playback::Track& track : out.tracks) {
      const auto ci = rig.find_channel(track.channel);
      if (!ci || rig.channels[*ci].digital()) continue;
      const auto& keys = track.raw.keys;
      for (std::size_t k = 0; k + 1 < keys.size(); ++k) {
        if (keys[k].interpolation == playback::Interpolation::step) continue;
        // Measured on its played part; stretched whole (keys outside the show included), so that
        // it keeps its shape.
        const auto span = detail::played_part(keys[k].time, keys[k + 1].time, out.duration);
        if (!span) continue;
        const double f = stretch_needed(measure(track.curve, span->t0, span->t1), rig.channels[*ci]);
        // A little more than just enough, so that the measurement's own rounding cannot leave a
        // segment a hair over the limit.
        if (f > 1 + 1e-9) spans.push_back({keys[k].time, keys[k + 1].time, f * (1 + 1e-6)});
      }
    }
    if (spans.empty()) break;
    const TimeWarp stretch = warp_for(spans);
    // The show still starts at 0: a stretch before it pushes earlier keys further back.
    const double zero = stretch(0);
    const auto warp = [&](double t) { return stretch(t) - zero; };
    for (playback::Track& track : out.tracks) {
      for (playback::RawKey& key : track.raw.keys) {
        // Handles move with the time around them, so a stretched segment keeps its shape.
        key.time = warp(key.time);
        if (key.left) key.left->time = warp(key.left->time);
        if (key.right) key.right->time = warp(key.right->time);
      }
      track.curve = playback::Curve::build(track.raw);
    }
    // Cues move with the time around them, as the keys do.
    for (playback::Cue& cue : out.cues) cue.time = warp(cue.time);
    for (playback::Marker& marker : out.markers) marker.time = warp(marker.time);
    out.duration = warp(out.duration);
  }
  return out;
}

}  // namespace avar::config
