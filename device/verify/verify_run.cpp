#include "verify_run.hpp"

#include "verify_lines.hpp"

#include "avar/device/curve_engine.hpp"
#include "avar/device/player.hpp"
#include "avar/device/show_image.hpp"

namespace avar {
namespace device {
namespace {

// xorshift32: the same sequence on every target.
struct Random {
  uint32_t state;
  uint32_t next() {
    state ^= state << 13;
    state ^= state >> 17;
    state ^= state << 5;
    return state;
  }
  /// Uniform enough in [0, n).
  uint32_t below(uint32_t n) { return next() % n; }
  /// In [lo, hi], hi - lo < 2^32 - 1 (unsigned arithmetic: no signed overflow on any target).
  int32_t between(int32_t lo, int32_t hi) {
    const uint32_t offset = below(static_cast<uint32_t>(hi) - static_cast<uint32_t>(lo) + 1u);
    return static_cast<int32_t>(static_cast<uint32_t>(lo) + offset);
  }
};

void add_sample(Hash& h, const Channel& ch, SegmentCache& cache, int32_t tick) {
  const int64_t q8 = sample_q8(ch, cache, tick);
  h.add(static_cast<uint32_t>(static_cast<uint64_t>(q8)), 4);
  h.add(static_cast<uint32_t>(static_cast<uint64_t>(q8) >> 32), 4);
  h.add(sample(ch, cache, tick), 2);
}

// A small image writer (the engine's format, show_image.hpp).
struct Writer {
  uint8_t* bytes;
  uint32_t at;
  void u8(uint32_t v) { bytes[at++] = static_cast<uint8_t>(v); }
  void fixed(uint32_t v, unsigned n) {
    for (unsigned i = 0; i < n; ++i) u8(v >> (8 * i));
  }
  void varint(uint64_t v) {
    while (v >= 0x80u) {
      u8(static_cast<uint32_t>(v & 0x7fu) | 0x80u);
      v >>= 7;
    }
    u8(static_cast<uint32_t>(v));
  }
  void zigzag(int64_t v) { varint(v >= 0 ? static_cast<uint64_t>(v) * 2u : static_cast<uint64_t>(-(v + 1)) * 2u + 1u); }
};

const int32_t kRandomValue = 70000;  // keys within +-70000 output units: most of the output, some beyond

// One random channel image in `buffer`; returns its size.
uint32_t random_image(Random& r, uint8_t* buffer) {
  static const uint32_t rates[] = {1000, 24000, 1000000};
  const uint32_t tps = rates[r.below(3)];
  Writer w = {buffer, 0};
  w.u8('a'), w.u8('v'), w.u8('d'), w.u8('1'), w.u8(kFormatVersion), w.u8(1), w.u8(0), w.u8(tps == 1000000 ? 1 : 0);
  w.fixed(tps, 4);
  w.fixed(tps * 10, 4);
  w.fixed(kHeaderSize + 4, 4);
  uint8_t flags = static_cast<uint8_t>(r.below(4));
  w.u8(flags);
  const uint32_t keys = 1 + r.below(6);
  w.fixed(keys, 2);
  if (flags & kChannelLinearExtrapolation)
    w.zigzag(r.between(-(INT32_C(1) << 30), INT32_C(1) << 30)), w.zigzag(r.between(-(INT32_C(1) << 30), INT32_C(1) << 30));
  if (flags & kChannelCycles) {
    w.u8(r.below(4) | (r.below(4) << 4));
    w.varint(r.below(3)), w.varint(r.below(3));
    w.zigzag(r.between(-(INT32_C(1) << 25), INT32_C(1) << 25));
  }
  int32_t value = r.between(-kRandomValue, kRandomValue);
  for (uint32_t i = 0; i < keys; ++i) {
    const bool last = i + 1 == keys;
    const uint32_t kind = last ? static_cast<uint32_t>(kStep) : r.below(kKindCount);
    const bool wide = kind == kBezier && r.below(2) == 1;
    w.u8(kind | (r.below(3) << 5) | (wide ? kKeyWideBezier : 0u));
    if (i == 0) {
      w.zigzag(r.between(-static_cast<int32_t>(tps), static_cast<int32_t>(tps)));
      w.zigzag(value);
    } else {
      w.varint(1 + r.below(tps * 2));
      const int32_t next = r.between(-kRandomValue, kRandomValue);
      w.zigzag(next - value);
      value = next;
    }
    if (kind == kCubic || kind == kBezier) {
      // Inner control points within 2^19 of their keys (and so within the engine's 2^20).
      w.zigzag(r.between(-(INT32_C(1) << 19) + kRandomValue, (INT32_C(1) << 19) - kRandomValue));
      w.zigzag(r.between(-(INT32_C(1) << 19) + kRandomValue, (INT32_C(1) << 19) - kRandomValue));
      if (kind == kBezier) {
        const uint32_t one = wide ? (UINT32_C(1) << 23) : (UINT32_C(1) << 15);
        w.fixed(r.below(one + 1), wide ? 3 : 2), w.fixed(r.below(one + 1), wide ? 3 : 2);
      }
    }
    if (kind == kBack) w.zigzag(r.between(-(INT32_C(1) << 18), INT32_C(1) << 18));
    if (kind == kElastic) {
      const bool blended = r.below(2) == 1;
      w.u8(blended ? 1 : 0);
      w.zigzag(blended ? r.between(0, INT32_C(1) << 30) : r.between(-(INT32_C(1) << 26), INT32_C(1) << 26));
      w.varint(1 + (static_cast<uint64_t>(r.next()) << r.below(4)));  // up to 16 durations
      w.zigzag(static_cast<int64_t>(r.between(-(INT32_C(1) << 30), INT32_C(1) << 30)) * static_cast<int64_t>(1 + r.below(8)));
    }
  }
  return w.at;
}

}  // namespace

void verify_image(const uint8_t* image, uint32_t size, int32_t step, LineSink sink, VerifyCounts& counts) {
  ShowHeader header;
  if (check_image(image, size, header) != kImageOk) {
    ++counts.invalid;
    line(sink, "golden-invalid ", 0, 0, 0);
    return;
  }
  const int32_t margin = static_cast<int32_t>(header.ticks_per_second) * 2;
  for (uint8_t c = 0; c < header.channel_count; ++c) {
    Channel ch;
    SegmentCache cache;
    reset_cache(cache);
    open_channel(image, size, c, ch);
    Hash h = {2166136261u};
    uint32_t samples = 0;
    for (int32_t tick = ch.start - margin; tick <= ch.end + margin; tick += step) {
      add_sample(h, ch, cache, tick);
      ++samples;
    }
    counts.samples += samples;
    line(sink, "golden ", c, h.value, samples);
  }
}

void verify_random(uint32_t seed, uint32_t curves, LineSink sink, VerifyCounts& counts) {
  Random r = {seed == 0 ? 1u : seed};
  uint8_t buffer[256];
  Hash h = {2166136261u};
  uint32_t samples = 0;
  for (uint32_t i = 0; i < curves; ++i) {
    const uint32_t size = random_image(r, buffer);
    Channel ch;
    if (!open_channel(buffer, size, 0, ch)) {
      ++counts.invalid;
    } else {
      SegmentCache cache;
      reset_cache(cache);
      const int64_t span = static_cast<int64_t>(ch.end) - ch.start + ch.ticks_per_second;
      for (int k = 0; k < 8; ++k) {
        const int64_t tick = static_cast<int64_t>(ch.start) - ch.ticks_per_second +
                             static_cast<int64_t>(r.next() % static_cast<uint32_t>(2 * span + 1));
        add_sample(h, ch, cache, static_cast<int32_t>(tick));
        ++samples;
      }
    }
    if ((i + 1) % 1000 == 0 || i + 1 == curves) {
      line(sink, "random ", i / 1000, h.value, samples);
      counts.samples += samples;
      samples = 0;
      h.value = 2166136261u;
    }
  }
}

void verify_player(uint32_t seed, uint32_t switches, LineSink sink, VerifyCounts& counts) {
  Random r = {seed == 0 ? 1u : seed};
  static uint8_t buffers[4][256];
  PlayerShow shows[4];
  for (int s = 0; s < 4; ++s) {
    shows[s].image = buffers[s];
    shows[s].size = random_image(r, buffers[s]);
  }
  PlayerChannel channel;
  const int64_t q16 = 65536;
  ChannelLimits limits;
  limits.low = static_cast<int64_t>(r.below(20000)) * q16;
  limits.high = limits.low + static_cast<int64_t>(1000 + r.below(40000)) * q16;
  limits.rest = limits.low + (limits.high - limits.low) / 3;
  limits.speed = static_cast<int64_t>(1 + r.below(2000)) * q16 / 4;
  limits.accel = static_cast<int64_t>(1 + r.below(400)) * q16 / 16;
  limiter_prepare(limits);
  static uint8_t stored[kLimitsSize];
  write_limits(limits, stored);
  channel.limits = stored;
  Player player;
  if (player_init(player, &channel, 1, shows, 4, 200) != kPlayerOk || player_start(player, 0) != kPlayerOk) {
    ++counts.invalid;
    return;
  }
  Hash h = {2166136261u};
  uint32_t ticks = 0;
  for (uint32_t i = 0; i < switches; ++i) {
    const uint32_t run = 1 + r.below(30);
    for (uint32_t k = 0; k < run; ++k) {
      const LimiterState before = channel.state;
      player_tick(player);
      ++ticks;
      const LimiterState& now = channel.state;
      const int64_t dv = now.velocity - before.velocity;
      const bool ok = now.position >= limits.low && now.position <= limits.high && now.velocity <= limits.speed &&
                      now.velocity >= -limits.speed && dv <= limits.accel && dv >= -limits.accel &&
                      now.position - before.position == now.velocity;
      if (!ok) ++counts.violations;
      h.add(channel.output, 2);
    }
    if (r.below(5) == 0) {
      player_stop(player);
    } else if (player_start(player, static_cast<uint8_t>(r.below(4))) != kPlayerOk) {
      ++counts.invalid;
    }
  }
  counts.samples += ticks;
  line(sink, "player ", switches, h.value, ticks);
}

void verify_summary(const VerifyCounts& counts, LineSink sink) {
  char text[64];
  char* at = put_text(text, "samples ");
  at = put_decimal(at, counts.samples);
  at = put_text(at, " invalid ");
  at = put_decimal(at, counts.invalid);
  at = put_text(at, " violations ");
  at = put_decimal(at, counts.violations);
  *at = 0;
  sink(text);
}

}  // namespace device
}  // namespace avar
