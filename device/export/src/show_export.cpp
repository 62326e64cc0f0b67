#include "avar/device/show_export.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>

#include "avar/core/format.hpp"
#include "avar/core/input_error.hpp"
#include "avar/device/show_image.hpp"
#include "little_endian.hpp"

namespace avar::device {
namespace {

using playback::Curve;
using playback::Interpolation;
using Kind = Curve::SegmentView::Kind;

constexpr double kMaxOutput = 1 << 20;  // the engine's bound on values and control points (output units)
// A Bezier segment's handle times take 16 bits each (Q15) unless that moves the curve by more than this
// (output units, estimated from the curve's slope): then 24 bits (Q23).
constexpr double kNarrowTimeError = 0.1;

void put_u8(std::vector<std::uint8_t>& out, unsigned v) { out.push_back(static_cast<std::uint8_t>(v)); }
void put_varint(std::vector<std::uint8_t>& out, std::uint64_t v) {
  while (v >= 0x80) {
    out.push_back(static_cast<std::uint8_t>(v | 0x80));
    v >>= 7;
  }
  out.push_back(static_cast<std::uint8_t>(v));
}
void put_zigzag(std::vector<std::uint8_t>& out, std::int64_t v) {
  put_varint(out, v >= 0 ? static_cast<std::uint64_t>(v) << 1 : (static_cast<std::uint64_t>(-(v + 1)) << 1) | 1);
}

std::int64_t rounded(double x) { return static_cast<std::int64_t>(std::llround(x)); }

std::uint8_t kind_of(Interpolation family) {
  switch (family) {
    case Interpolation::sine: return kSine;
    case Interpolation::quad: return kQuad;
    case Interpolation::cubic: return kCubicEase;
    case Interpolation::quart: return kQuart;
    case Interpolation::quint: return kQuint;
    case Interpolation::expo: return kExpo;
    case Interpolation::circ: return kCirc;
    case Interpolation::back: return kBack;
    case Interpolation::bounce: return kBounce;
    case Interpolation::elastic: return kElastic;
    default: return kLinear;
  }
}

std::uint8_t easing_bits(playback::Easing e) {
  switch (e) {
    case playback::Easing::ease_out: return kEaseOut;
    case playback::Easing::ease_in_out: return kEaseInOut;
    default: return kEaseIn;
  }
}

std::uint8_t cycle_mode(playback::CycleMode m) {
  switch (m) {
    case playback::CycleMode::repeat: return kCycleRepeat;
    case playback::CycleMode::repeat_offset: return kCycleRepeatOffset;
    case playback::CycleMode::mirror: return kCycleMirror;
    default: return kCycleNone;
  }
}

// How far (output units) 16-bit handle times move a Bezier segment: the time error of the
// rounded handles times the curve's slope in normalised time, at 33 points of the parameter.
double narrow_time_error(double a, double b, double e1, double e2, double e3) {
  const double da = std::abs(a - std::round(a * 32768) / 32768), db = std::abs(b - std::round(b * 32768) / 32768);
  double worst = 0;
  for (int i = 1; i < 32; ++i) {
    const double u = i / 32.0, w = 1 - u;
    const double ds = 3 * u * w * w * da + 3 * u * u * w * db;
    const double slope_s = 3 * a * w * w + 6 * (b - a) * u * w + 3 * (1 - b) * u * u;
    const double slope_v = std::abs(e1 + u * (2 * e2 + 3 * u * e3));
    worst = std::max(worst, slope_v * ds / std::max(slope_s, 1e-6));
  }
  return worst;
}

// avar's key snap (Curve::kKeySnap) in whole ticks: 1 at a microsecond per tick, else 0.
std::uint8_t snap_ticks(std::uint32_t ticks_per_second) {
  return static_cast<std::uint8_t>(std::floor(Curve::kKeySnap * ticks_per_second + 1e-9));
}

std::string at_key(const playback::RawCurve& raw, std::size_t i) {
  return "key " + std::to_string(i + 1) + " (" + format_number(raw.keys[i].time) + " s)";
}

}  // namespace

std::uint32_t choose_ticks_per_second(const std::vector<double>& times_s) {
  for (const std::uint32_t rate : kTickRates) {
    const bool whole = std::all_of(times_s.begin(), times_s.end(), [&](double t) {
      const double ticks = t * rate;
      return std::abs(ticks - std::round(ticks)) <= 1e-4;
    });
    if (whole) return rate;
  }
  return kTickRates[std::size(kTickRates) - 1];
}

std::vector<std::uint8_t> encode_channel_record(const playback::RawCurve& raw, const Curve& curve, OutputRange range,
                                                std::uint32_t ticks_per_second, ShowImage* counts) {
  const std::uint32_t tps = ticks_per_second;
  if (!(range.high > range.low) || !std::isfinite(range.low) || !std::isfinite(range.high))
    throw InputError(raw.where, "the channel's range " + format_number(range.low) + " to " + format_number(range.high) +
                                    " cannot be mapped to 16-bit output; expected min below max");
  const std::size_t n = raw.keys.size();
  const double scale = 65535.0 / (range.high - range.low);
  std::vector<std::uint8_t> out;
  std::uint8_t flags = 0;
  const bool linear = curve.slope_before() != 0 || curve.slope_after() != 0;
  const playback::Cycles& cycles = curve.cycles();
  if (linear) flags |= kChannelLinearExtrapolation;
  if (cycles.any()) flags |= kChannelCycles;
  put_u8(out, flags);
  put_fixed(out, n, 2);
  if (n > 0xffff)
    throw InputError(raw.where,
                     "the curve has " + std::to_string(n) + " keys; the device engine plays at most 65535 per channel");
  const auto slope_q8 = [&](double slope) {
    const double q8 = slope * scale * 256;
    if (!(std::abs(q8) <= 1e12))
      throw InputError(raw.where, "the curve's extrapolation slope is too steep for the device engine");
    return rounded(q8);
  };
  if (linear) {
    put_zigzag(out, slope_q8(curve.slope_before()));
    put_zigzag(out, slope_q8(curve.slope_after()));
  }
  if (cycles.any()) {
    put_u8(out, cycle_mode(cycles.before) | (cycle_mode(cycles.after) << 4));
    put_varint(out, static_cast<std::uint64_t>(cycles.before_count));
    put_varint(out, static_cast<std::uint64_t>(cycles.after_count));
    const double change = curve.evaluate(curve.end_time()) - curve.evaluate(curve.start_time());
    put_zigzag(out, rounded(change * scale * 256));
  }
  // Key ticks and values (output units): a key's value is where its segment starts; the last
  // key's is the curve's value there.
  std::vector<std::int64_t> ticks(n), values(n);
  const auto output = [&](double v, std::size_t key, const char* what = "") {
    const double o = range.to_output(v);
    if (!(std::abs(o) <= kMaxOutput))
      throw InputError(raw.keys[key].where, at_key(raw, key) + what + " reaches " + format_number(v) +
                                                ", more than 16 times the channel's range away from it; the device engine's "
                                                "values and control points stay within 16 ranges");
    return o;
  };
  for (std::size_t i = 0; i < n; ++i) {
    const double t = raw.keys[i].time * tps;
    if (!(std::abs(t) < 2147483647.0))
      throw InputError(raw.keys[i].where, at_key(raw, i) + " lies beyond the device's 32-bit clock at " + std::to_string(tps) +
                                              " ticks per second (" + format_number(2147483647.0 / tps) + " s)");
    ticks[i] = rounded(t);
    if (i > 0 && ticks[i] <= ticks[i - 1])
      throw InputError(raw.keys[i].where, at_key(raw, i) + " is less than a tick (1/" + std::to_string(tps) +
                                              " s) after the key before it; expected keys at least a tick apart");
    const double v = i + 1 < n ? curve.segment_view(i).v0 : curve.evaluate(raw.keys[i].time);
    values[i] = rounded(output(v, i));
  }
  std::size_t key_bytes = 0;
  // The handle times of the channel's last Bezier key, as encoded.
  struct HandleTimes {
    std::uint32_t a, b;
    bool wide;
    bool operator==(const HandleTimes&) const = default;
  };
  std::optional<HandleTimes> previous_times;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t begin = out.size();
    std::vector<std::uint8_t> params;
    std::uint8_t header = kStep;
    if (i + 1 < n) {
      const Curve::SegmentView s = curve.segment_view(i);
      // Where the segment ends must be where the next starts: the engine joins them at one value.
      const double end = s.kind == Kind::cubic || s.kind == Kind::bezier ? s.v0 + s.e1 + s.e2 + s.e3
                         : s.kind == Kind::constant                      ? curve.segment_view(i).v0
                                                                         : s.v0 + s.e1;
      if (s.kind != Kind::constant && std::abs(range.to_output(end) - static_cast<double>(values[i + 1])) > 0.5 + 1e-6)
        throw InputError(raw.keys[i + 1].where, at_key(raw, i + 1) +
                                                    ": the curve jumps there (a B-spline beside another family); "
                                                    "the device engine joins segments at their keys");
      const auto inner = [&](double e1, double e2) {
        const double p1 = range.to_output(s.v0 + e1 / 3), p2 = range.to_output(s.v0 + (2 * e1 + e2) / 3);
        output(s.v0 + e1 / 3, i, ": the control point after it"),
            output(s.v0 + (2 * e1 + e2) / 3, i, ": the control point before the next key");
        put_zigzag(params, rounded(p1) - values[i]);
        put_zigzag(params, rounded(p2) - values[i + 1]);
      };
      switch (s.kind) {
        case Kind::constant: header = kStep; break;
        case Kind::linear: header = kLinear; break;
        case Kind::cubic:
          header = kCubic;
          inner(s.e1, s.e2);
          break;
        case Kind::bezier: {
          header = kBezier;
          double a = s.k1 / 3, b = (s.k2 + 2 * s.k1) / 3;
          if (a < -1e-12 || b < -1e-12 || a > 1 + 1e-12 || b > 1 + 1e-12)
            throw InputError(raw.keys[i].where, at_key(raw, i) +
                                                    ": a handle of its Bezier segment points back in time; "
                                                    "the device engine plays Bezier segments whose time runs forward");
          a = std::clamp(a, 0.0, 1.0), b = std::clamp(b, 0.0, 1.0);
          inner(s.e1, s.e2);
          // Handles at a third of the segment each: time runs linearly, u = s, and the segment is
          // the cubic family, without the handle times.
          if (std::abs(a - 1.0 / 3) < 1e-9 && std::abs(b - 2.0 / 3) < 1e-9) {
            header = kCubic;
            break;
          }
          const bool wide = narrow_time_error(a, b, s.e1 * scale, s.e2 * scale, s.e3 * scale) > kNarrowTimeError;
          const int bytes = wide ? 3 : 2;
          const auto fraction = [&](double x) { return static_cast<std::uint32_t>(rounded(std::ldexp(x, 8 * bytes - 1))); };
          const HandleTimes times{fraction(a), fraction(b), wide};
          if (wide) header |= kKeyWideBezier;
          if (previous_times && *previous_times == times) {
            header |= kKeySameHandleTimes;  // Blender's auto handles between evenly spaced keys: 4 bytes less
          } else {
            put_fixed(params, times.a, bytes);
            put_fixed(params, times.b, bytes);
          }
          previous_times = times;
          if (counts) ++counts->bezier_keys;
          break;
        }
        case Kind::easing: {
          header = kind_of(s.family) | static_cast<std::uint8_t>(easing_bits(s.easing) << 5);
          if (s.family == Interpolation::back) put_zigzag(params, rounded(s.back * 65536));
          if (s.family == Interpolation::elastic) {
            // Blender's elastic numbers (playback/runtime/src/easing.cpp), in units of the duration.
            const double change = s.e1, duration = s.t1 - s.t0;
            double period = s.period / duration;
            if (period == 0) period = s.easing == playback::Easing::ease_in_out ? 0.3 * 1.5 : 0.3;
            if (!(period > 0 && period < 1048576))
              throw InputError(raw.keys[i].where, at_key(raw, i) + ": the elastic period is more than 2^20 times its segment");
            const bool blended = s.amplitude == 0 || s.amplitude < std::abs(change);
            const double shift = blended ? period / 4 : period / (2 * std::numbers::pi) * std::asin(change / s.amplitude);
            put_u8(params, blended ? 1 : 0);
            if (blended) {
              put_zigzag(params,
                         change == 0 ? rounded(std::ldexp(1.0, 30)) : rounded(std::ldexp(s.amplitude / std::abs(change), 30)));
            } else {
              put_zigzag(params, rounded(s.amplitude * scale * 256));
            }
            put_varint(params, static_cast<std::uint64_t>(rounded(std::ldexp(period, 30))));
            put_zigzag(params, rounded(std::ldexp(shift, 30)));
          }
          break;
        }
      }
    }
    put_u8(out, header);
    if (i == 0) {
      put_zigzag(out, ticks[0]);
      put_zigzag(out, values[0]);
    } else {
      put_varint(out, static_cast<std::uint64_t>(ticks[i] - ticks[i - 1]));
      put_zigzag(out, values[i] - values[i - 1]);
    }
    out.insert(out.end(), params.begin(), params.end());
    key_bytes += out.size() - begin;
  }
  if (counts) {
    counts->keys += n;
    counts->key_bytes += key_bytes;
  }
  return out;
}

ChannelLimits device_limits(OutputRange range, double rest, double max_velocity, double max_acceleration, double soft_margin,
                            std::uint32_t rate) {
  const double q16 = 65536.0, scale = 65535.0 / (range.high - range.low);
  if (!(max_velocity > 0) || !(max_acceleration > 0) || !(soft_margin >= 0) || rate == 0 || !(range.high > range.low))
    throw std::invalid_argument(
        "a channel's device limits need min below max, speed and acceleration above 0, a margin of 0 or more");
  ChannelLimits l;
  l.low = rounded(soft_margin * scale * q16);
  l.high = rounded((65535.0 - soft_margin * scale) * q16);
  l.rest = rounded(range.to_output(rest) * q16);
  if (!(l.low <= l.rest && l.rest <= l.high))
    throw std::invalid_argument("a channel's rest pose lies outside its range less its soft margin");
  // At least one Q16 step per tick: a limit below it would freeze the channel.
  l.speed = std::max<std::int64_t>(1, rounded(max_velocity * scale / rate * q16));
  l.accel = std::max<std::int64_t>(1, rounded(max_acceleration * scale / (static_cast<double>(rate) * rate) * q16));
  limiter_prepare(l);
  return l;
}

ChannelLimits streaming_limits(OutputRange range, double rest, double max_velocity, double max_acceleration, double soft_margin,
                               std::uint32_t rate) {
  return device_limits(range, rest, max_velocity, max_acceleration * kStreamAccelHeadroom, soft_margin, rate);
}

std::vector<std::uint8_t> single_channel_image(const std::vector<std::uint8_t>& record, std::uint32_t ticks_per_second,
                                               std::int32_t duration_ticks) {
  std::vector<std::uint8_t> out = {'a', 'v', 'd', '1', kFormatVersion, 1, 0, snap_ticks(ticks_per_second)};
  put_fixed(out, ticks_per_second, 4);
  put_fixed(out, static_cast<std::uint32_t>(duration_ticks), 4);
  put_fixed(out, kHeaderSize + 4, 4);
  out.insert(out.end(), record.begin(), record.end());
  return out;
}

ShowImage encode_show_image(const playback::Show& show, const std::vector<ImageChannel>& channels, const ImageOptions& options) {
  if (show.layered() || !show.targets.empty())
    throw InputError(show.where,
                     "show '" + show.name +
                         "' has layers or targets; the device engine plays a show's tracks (compose them on the host: "
                         "avar record, or bake the layers into tracks)");
  if (channels.empty() || channels.size() > kMaxChannels)
    throw InputError(show.where, "expected 1 to " + std::to_string(kMaxChannels) + " channels for the device, found " +
                                     std::to_string(channels.size()));
  std::vector<const playback::Track*> tracks;
  std::vector<double> times = options.on_grid;
  times.push_back(show.duration);
  for (const ImageChannel& c : channels) {
    const auto found = std::find_if(show.tracks.begin(), show.tracks.end(), [&](const auto& t) { return t.channel == c.name; });
    if (found == show.tracks.end())
      throw InputError(show.where, "show '" + show.name + "' has no track for channel '" + c.name + "'");
    tracks.push_back(&*found);
    for (const auto& k : found->raw.keys) times.push_back(k.time);
  }
  ShowImage image;
  image.ticks_per_second = options.ticks_per_second != 0 ? options.ticks_per_second : choose_ticks_per_second(times);
  const std::uint32_t tps = image.ticks_per_second;
  const double duration = std::round(show.duration * tps);
  if (!(duration < 2147483647.0))
    throw InputError(show.where, "show '" + show.name + "' lasts beyond the device's 32-bit clock at " + std::to_string(tps) +
                                     " ticks per second");
  std::vector<std::uint8_t>& out = image.bytes;
  out = {'a',
         'v',
         'd',
         '1',
         kFormatVersion,
         static_cast<std::uint8_t>(channels.size()),
         static_cast<std::uint8_t>(show.loop ? kShowLoops : 0),
         snap_ticks(tps)};
  put_fixed(out, tps, 4);
  put_fixed(out, static_cast<std::uint32_t>(static_cast<std::int32_t>(duration)), 4);
  const std::size_t offsets = out.size();
  out.resize(out.size() + 4 * channels.size());
  for (std::size_t c = 0; c < channels.size(); ++c) {
    const std::vector<std::uint8_t> record =
        encode_channel_record(tracks[c]->raw, tracks[c]->curve, channels[c].range, tps, &image);
    const auto at = static_cast<std::uint32_t>(out.size());
    for (int b = 0; b < 4; ++b) out[offsets + 4 * c + b] = static_cast<std::uint8_t>(at >> (8 * b));
    out.insert(out.end(), record.begin(), record.end());
  }
  return image;
}

}  // namespace avar::device
