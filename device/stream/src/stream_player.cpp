#include "avar/device/stream_player.hpp"

#include "avar/device/fixed_math.hpp"

namespace avar {
namespace device {
namespace wire = firmware_iface::avar_device;
static_assert(wire::kSlopeUnit == 8, "knot_cubic_q8's constant: a third of a second's worth of 8 units, in Q8");

namespace {

/// a - b as a signed span of the wrapping clock (times within 2^31 µs of each other).
int32_t since(uint32_t a, uint32_t b) {
  const uint32_t d = a - b;
  return d < 0x80000000u ? static_cast<int32_t>(d) : -static_cast<int32_t>(0xffffffffu - d) - 1;
}

/// Outputs off: released by avar (until a hello), or failed (until a reset).
bool off(const StreamPlayer& p) { return p.state == wire::kReleased || p.state == wire::kFault; }

uint8_t ring_index(const StreamPlayer& p, uint8_t i) { return static_cast<uint8_t>((p.head + i) % p.capacity); }
wire::Knot* frame_knots(StreamPlayer& p, uint8_t i) { return p.knots + static_cast<size_t>(ring_index(p, i)) * p.channel_count; }

int64_t lerp_q16(int64_t a, int64_t b, int64_t s) { return a + shift_floor((b - a) * s, 16); }

void take_knots(StreamPlayer& p, const uint8_t* payload, uint8_t length) {
  if (off(p) || !p.clock_set) return;
  uint32_t time = 0;
  uint8_t count = 0;
  if (!wire::read_knots_header(payload, length, time, count) || count != p.channel_count) return;
  if (p.state != wire::kStreaming) p.count = 0;  // a new stream: nothing of an old one is played
  if (p.count > 0) {
    const int32_t after = since(time, p.times[ring_index(p, static_cast<uint8_t>(p.count - 1))]);
    if (after == 0) {
      --p.count;  // the same knot again: the newer replaces it
    } else if (after < 0) {
      p.count = 0;  // avar's stream started over
    }
  }
  if (p.count == p.capacity) return;  // ahead of what the device holds: avar sends too early
  // Decoded straight into its ring slot (no copy on the stack: a device's RAM is small).
  if (!wire::read_knots(payload, length, time, frame_knots(p, p.count), count, count)) return;
  p.times[ring_index(p, p.count)] = time;
  ++p.count;
  p.state = wire::kStreaming;
}

void take_time(StreamPlayer& p, const uint8_t* payload, uint8_t length, uint32_t now_us) {
  uint32_t host = 0;
  if (!wire::read_time(payload, length, host)) return;
  const int32_t error = since(host, now_us + p.offset);  // > 0: the device's clock is behind
  if (!p.clock_set || error > static_cast<int32_t>(kClockStepUs) || error <= -static_cast<int32_t>(kClockRestartUs)) {
    p.offset += static_cast<uint32_t>(error);
    p.clock_set = true;
  } else if (error > 0) {
    p.offset += static_cast<uint32_t>(error / 2);
  } else {
    p.offset -= static_cast<uint32_t>(-error / 64);
  }
}

uint16_t status_reply(const StreamPlayer& p, uint32_t now_us, uint8_t* reply) {
  wire::Status s;
  s.version = wire::kVersion;
  s.channel_count = p.channel_count;
  s.rate_hz = p.rate;
  s.knot_capacity = p.capacity;
  s.state = p.state;
  s.bad_frames = static_cast<uint16_t>(p.parser.bad_frames > 0xffffu ? 0xffffu : p.parser.bad_frames);
  s.time_us = stream_time(p, now_us);
  return static_cast<uint16_t>(wire::encode_status(s, reply));
}

uint16_t positions_reply(const StreamPlayer& p, uint8_t* reply) {
  uint16_t outputs[wire::kMaxChannels];
  const uint8_t n = p.channel_count < wire::kMaxChannels ? p.channel_count : wire::kMaxChannels;
  for (uint8_t c = 0; c < n; ++c) outputs[c] = p.channels[c].output;
  return static_cast<uint16_t>(wire::encode_positions(outputs, n, reply));
}

/// The target of channel c at stream time t, Q8 output units, from the knots held (count > 0).
int64_t knot_target(StreamPlayer& p, uint8_t c, uint32_t t) {
  const uint32_t t0 = p.times[ring_index(p, 0)];
  const wire::Knot& a = frame_knots(p, 0)[c];
  if (p.count >= 2 && since(t, t0) >= 0) {
    const uint32_t t1 = p.times[ring_index(p, 1)];
    if (static_cast<uint32_t>(since(t1, t0)) <= kMaxKnotGapUs) return knot_cubic_q8(t0, a, t1, frame_knots(p, 1)[c], t);
  }
  return static_cast<int64_t>(a.value) * 256;  // before the first knot, or the last one held
}

}  // namespace

StreamStatus stream_init(StreamPlayer& p, StreamChannel* channels, uint8_t channel_count, uint32_t* times, wire::Knot* knots,
                         uint8_t capacity, uint8_t* frame, uint16_t rate, uint32_t watchdog_us) {
  p.channels = channels;
  p.channel_count = channel_count;
  p.times = times;
  p.knots = knots;
  p.capacity = capacity;
  p.head = 0;
  p.count = 0;
  p.rate = rate;
  p.watchdog_us = watchdog_us;
  p.state = wire::kResting;
  p.clock_set = false;
  p.offset = 0;
  p.last_heard = 0;
  p.underruns = 0;
  if (channel_count == 0 || channel_count > wire::kMaxChannels || rate == 0) return kStreamBadChannels;
  if (capacity < 2 || times == nullptr || knots == nullptr || frame == nullptr) return kStreamBadStorage;
  wire::parser_reset(p.parser, frame, static_cast<uint8_t>(stream_frame_room(channel_count)));
  for (uint8_t c = 0; c < channel_count; ++c) {
    const ChannelLimits limits = read_limits(channels[c].limits);
    if (!limits_usable(limits)) return kStreamBadLimits;
    channels[c].state = limiter_at_rest(limits);
    channels[c].output = limiter_output(channels[c].state);
    channels[c].released = false;
  }
  return kStreamOk;
}

uint16_t stream_receive(StreamPlayer& p, uint8_t byte, uint32_t now_us, uint8_t* reply) {
  if (!wire::parser_push(p.parser, byte)) return 0;
  p.last_heard = now_us;
  const uint8_t* payload = p.parser.payload;
  const uint8_t length = p.parser.length;
  switch (p.parser.type) {
    case wire::kHello: {
      uint8_t version = 0;
      if (!wire::read_hello(payload, length, version)) return 0;
      if (p.state != wire::kFault) {
        if (p.state == wire::kReleased) p.state = wire::kResting;
        for (uint8_t c = 0; c < p.channel_count; ++c) p.channels[c].released = false;
      }
      return status_reply(p, now_us, reply);
    }
    case wire::kTime: take_time(p, payload, length, now_us); return 0;
    case wire::kKnots: take_knots(p, payload, length); return 0;
    case wire::kStop:
      if (length == 0 && !off(p)) {
        p.count = 0;
        if (p.state == wire::kStreaming) p.state = wire::kStopping;
      }
      return 0;
    case wire::kRelease:
      if (p.state == wire::kFault) return 0;
      if (length == 0) {
        p.count = 0;
        p.state = wire::kReleased;
        for (uint8_t c = 0; c < p.channel_count; ++c) p.channels[c].released = true;
      } else if (length == (p.channel_count + 7u) / 8u) {
        for (uint8_t c = 0; c < p.channel_count; ++c)
          if (payload[c / 8u] & (1u << (c % 8u))) p.channels[c].released = true;
      }
      return 0;
    case wire::kQuery: return length == 0 ? positions_reply(p, reply) : 0;
    default: return 0;
  }
}

void stream_fault(StreamPlayer& p) {
  p.state = wire::kFault;
  p.count = 0;
  for (uint8_t c = 0; c < p.channel_count; ++c) p.channels[c].released = true;
}

void stream_tick(StreamPlayer& p, uint32_t now_us) {
  if (off(p)) return;
  if (p.state == wire::kStreaming && p.watchdog_us != 0 && static_cast<uint32_t>(now_us - p.last_heard) > p.watchdog_us) {
    p.state = wire::kStopping;  // avar went silent: to rest
    p.count = 0;
  }
  const uint32_t t = stream_time(p, now_us);
  if (p.state == wire::kStreaming) {
    while (p.count >= 2 && since(t, p.times[ring_index(p, 1)]) >= 0) {
      p.head = ring_index(p, 1);
      --p.count;
    }
    if (p.count == 1 && since(t, p.times[p.head]) > 0) ++p.underruns;
  }
  bool resting = true;
  for (uint8_t c = 0; c < p.channel_count; ++c) {
    StreamChannel& ch = p.channels[c];
    if (ch.released) continue;
    const ChannelLimits limits = read_limits(ch.limits);
    const int64_t target = p.state == wire::kStreaming ? knot_target(p, c, t) * 256 : limits.rest;
    limiter_step(limits, ch.state, target);
    ch.output = limiter_output(ch.state);
    resting = resting && ch.state.position == limits.rest && ch.state.velocity == 0;
  }
  if (p.state == wire::kStopping && resting) p.state = wire::kResting;
}

int64_t knot_cubic_q8(uint32_t t0, const wire::Knot& a, uint32_t t1, const wire::Knot& b, uint32_t time_us) {
  const uint32_t span = t1 - t0;
  if (span == 0) return static_cast<int64_t>(b.value) * 256;
  uint32_t at = time_us - t0;
  if (at > span) at = span;
  const int64_t s = static_cast<int64_t>((static_cast<uint64_t>(at) * 65536u) / span);  // Q16
  // A third of the span along each slope (kSlopeUnit output units per second, Q8): slope * 8 *
  // span / 10^6 / 3 * 256 = slope * span * 256 / 375000, toward zero.
  const int64_t p0 = static_cast<int64_t>(a.value) * 256, p3 = static_cast<int64_t>(b.value) * 256;
  const int64_t p1 = p0 + static_cast<int64_t>(a.slope) * span * 256 / 375000;
  const int64_t p2 = p3 - static_cast<int64_t>(b.slope) * span * 256 / 375000;
  const int64_t q0 = lerp_q16(p0, p1, s), q1 = lerp_q16(p1, p2, s), q2 = lerp_q16(p2, p3, s);
  const int64_t r0 = lerp_q16(q0, q1, s), r1 = lerp_q16(q1, q2, s);
  return lerp_q16(r0, r1, s);
}

}  // namespace device
}  // namespace avar
