#pragma once
// The device's side of the avar-device streaming protocol (avar_device_codec.hpp): avar sends
// knots (a time, and each channel's value and slope) ahead of time and its clock; the device
// plays, at its own control rate, the cubic between the two knots around its stream time (the
// Hermite cubic of their values and slopes) through its limiter (limiter.hpp), so a slow link
// carries a few knots a second and the motion stays smooth. One source for the device and the
// simulated device (`avar sim avar-device`). Freestanding C++14, caller-owned storage, no heap.
//
// Safety, on the device: every output has passed the channel's limiter (range, speed,
// acceleration); power-up rests every channel; knots that run out hold the last knot's value; a
// link silent for the watchdog time, or kStop, eases every channel to rest; kRelease turns
// outputs off (all, or some channels) until the next kHello: a released channel's output does not
// change and the caller sends it no pulse. A fault of the device's own (stream_fault: a servo board
// that does not answer) turns every output off until the device is reset, and its status says so. Bad frames are dropped whole
// (the parser's CRC).
//
// Time: `now_us` is the device's own microsecond counter (micros(); it may wrap). Stream time is
// now_us plus an offset that kTime messages keep: a message can only arrive late (the link's
// latency), never early, so one that finds the device's clock behind moves it up at once (half the
// error, or all of it past kClockStepUs), and one that finds it ahead trims it back slowly (a
// sixty-fourth), unless it is a second or more ahead (avar started over): the clock follows the
// earliest arrivals, and a late message (a busy PC, a USB adapter's latency timer) barely moves it.

#include <stdint.h>

#include "avar/device/limiter.hpp"
#include "avar/firmware_iface/avar_device_codec.hpp"

namespace avar {
namespace device {

/// The device's clock behind avar's by more than this is set, not trimmed.
const uint32_t kClockStepUs = 20000;
/// The device's clock ahead of avar's by this much or more is set too: avar's stream started over.
const uint32_t kClockRestartUs = 1000000;
/// Two knots farther apart than this (µs) are not joined: the later one is held from its time.
const uint32_t kMaxKnotGapUs = 4000000;

/// One channel of the streaming device.
struct StreamChannel {
  const uint8_t* limits;  ///< stored limits (kLimitsSize bytes, write_limits), read each tick
  LimiterState state;
  uint16_t output;  ///< the last tick's 16-bit command
  bool released;    ///< its output is off (kRelease) until the next kHello
};

struct StreamPlayer {
  StreamChannel* channels;
  uint8_t channel_count;
  // The knots ahead: a ring of `capacity` frames, each a time and channel_count knots.
  uint32_t* times;
  firmware_iface::avar_device::Knot* knots;
  uint8_t capacity, head, count;
  uint16_t rate;         ///< control ticks per second
  uint32_t watchdog_us;  ///< link silence that eases to rest (0: never)
  uint8_t state;         ///< avar_device::State
  bool clock_set;        ///< a kTime has set the offset
  uint32_t offset;       ///< stream time - now_us (mod 2^32)
  uint32_t last_heard;   ///< now_us of the last good frame
  uint32_t underruns;    ///< ticks that found no knot after the stream time
  firmware_iface::avar_device::Parser parser;
};

enum StreamStatus : uint8_t { kStreamOk = 0, kStreamBadChannels, kStreamBadLimits, kStreamBadStorage };

/// Sets the player up at rest. `times` holds `capacity` (at least 2) entries, `knots`
/// capacity * channel_count, `frame` stream_frame_room(channel_count) bytes (the parser's);
/// every channel's limits must be usable as the player's (player.hpp).
StreamStatus stream_init(StreamPlayer& player, StreamChannel* channels, uint8_t channel_count, uint32_t* times,
                         firmware_iface::avar_device::Knot* knots, uint8_t capacity, uint8_t* frame, uint16_t rate,
                         uint32_t watchdog_us);

/// The room the longest message a device of `channel_count` channels takes needs: a knots frame
/// (its parser's buffer; one expression, for C++11).
constexpr uint16_t stream_frame_room(uint8_t channel_count) {
  return static_cast<uint16_t>(firmware_iface::avar_device::kOverhead + 5u + 4u * channel_count);
}

/// The room an answer of a device of `channel_count` channels takes: its status or its positions
/// (one expression, for the C++11 that Arduino cores compile sketches with).
constexpr uint16_t stream_reply_room(uint8_t channel_count) {
  return static_cast<uint16_t>(firmware_iface::avar_device::kOverhead +
                               (1u + 2u * channel_count > firmware_iface::avar_device::kStatusSize
                                    ? 1u + 2u * channel_count
                                    : firmware_iface::avar_device::kStatusSize));
}

/// Takes one byte from the link at `now_us`. When it completes a frame that asks for an answer,
/// writes the answer's frame into `reply` (room for stream_reply_room(channel_count) bytes) and
/// returns its size; otherwise 0.
uint16_t stream_receive(StreamPlayer& player, uint8_t byte, uint32_t now_us, uint8_t* reply);

/// A fault of the device's own: every channel released (the caller switches its outputs off) and
/// the state kFault, which no message leaves (the device answers hello and query, and takes no
/// knots) until stream_init runs again.
void stream_fault(StreamPlayer& player);

/// One control tick at `now_us`: each channel's target (the knots' cubic at stream time, the last
/// knot held, or rest), through the limiter. Nothing moves while released.
void stream_tick(StreamPlayer& player, uint32_t now_us);

/// The stream time at `now_us`.
inline uint32_t stream_time(const StreamPlayer& player, uint32_t now_us) { return now_us + player.offset; }

/// The value (Q8 output units) at `time_us` of the cubic between knots a (at t0) and b (at t1 >
/// t0): Hermite in value and slope, as a Bezier with its inner points a third of the span along
/// the slopes, evaluated by de Casteljau in Q16 of the span. Exact at both knots.
int64_t knot_cubic_q8(uint32_t t0, const firmware_iface::avar_device::Knot& a, uint32_t t1,
                      const firmware_iface::avar_device::Knot& b, uint32_t time_us);

}  // namespace device
}  // namespace avar
