#pragma once
// The avar-device streaming protocol (docs/protocols/avar-device.md): avar sends a
// device running its player curve knots (a time, and each channel's value and slope) and its
// clock, not positions; the device plays the cubic between consecutive knots at its own control
// rate, through its own limiter. Pure functions from messages to frames and back, and a parser
// that finds frames in a byte stream. One source for the host's link, the simulated device and
// the device: freestanding C++14, <stdint.h> and <stddef.h> only, no allocation.
//
// Frame: 0xA5, u8 type, u8 payload length (0..kMaxPayload), the payload, u16 CRC-16/CCITT-FALSE
// (polynomial 0x1021, initial 0xFFFF, not reflected) of type, length and payload. Little-endian.

#include <stddef.h>
#include <stdint.h>

namespace avar {
namespace firmware_iface {
namespace avar_device {

const uint8_t kStart = 0xa5;
const uint8_t kVersion = 1;
const uint8_t kMaxPayload = 250;
const size_t kOverhead = 5;  ///< start, type, length, CRC
const size_t kMaxFrame = kMaxPayload + kOverhead;
/// A knot frame carries every channel of the device: at most this many (payload 5 + 4 per channel).
const uint8_t kMaxChannels = 61;
/// A knot's slope counts in steps of this many output units per second.
const int32_t kSlopeUnit = 8;

enum Type : uint8_t {
  // avar to the device
  kHello = 0x01,    ///< u8 version: the device answers kStatus
  kTime = 0x02,     ///< u32 avar's stream time now (µs): the device's clock follows it
  kKnots = 0x03,    ///< u32 time (µs), u8 channel count, per channel u16 value, i16 slope
  kStop = 0x04,     ///< ease every channel to rest, knots dropped
  kRelease = 0x05,  ///< outputs off (servos limp) until the next kHello: every one, or those whose
                    ///< bit is set in a mask of (channels + 7) / 8 bytes (bit c % 8 of byte c / 8)
  kQuery = 0x06,    ///< the device answers kPositions
  // the device to avar
  kStatus = 0x81,     ///< see Status
  kPositions = 0x82,  ///< u8 channel count, per channel u16 output (its limiter's present output)
};

/// What the device is doing (Status::state).
enum State : uint8_t {
  kResting = 0,    ///< at rest, no knots
  kStreaming = 1,  ///< playing knots
  kStopping = 2,   ///< easing to rest (kStop, the watchdog, or the knots ran out)
  kReleased = 3,   ///< outputs off
  kFault = 4,      ///< outputs off for a fault of the device's own (a servo board that does not answer), until it is reset
};

/// One channel's knot: where it is at the knot's time, and how fast it moves there.
struct Knot {
  uint16_t value;  ///< output units: 0..65535 over the channel's range
  int16_t slope;   ///< kSlopeUnit output units per second
};

struct Status {
  uint8_t version;
  uint8_t channel_count;
  uint16_t rate_hz;       ///< the device's control ticks per second
  uint8_t knot_capacity;  ///< knot frames the device holds ahead
  uint8_t state;          ///< State
  uint16_t bad_frames;    ///< frames dropped for their CRC or length since power-up (saturates)
  uint32_t time_us;       ///< the device's stream time when it answered
};
const uint8_t kStatusSize = 12;

/// CRC-16/CCITT-FALSE of `length` bytes, continuing from `crc` (start with 0xFFFF).
uint16_t crc16(uint16_t crc, const uint8_t* bytes, size_t length);

/// Writes one frame of `type` with `payload` into `out` (room for length + kOverhead bytes);
/// returns its size, or 0 for a payload longer than kMaxPayload.
size_t encode_frame(uint8_t type, const uint8_t* payload, uint8_t length, uint8_t* out);

size_t encode_hello(uint8_t* out);
size_t encode_time(uint32_t time_us, uint8_t* out);
/// 0 for no channels or more than kMaxChannels.
size_t encode_knots(uint32_t time_us, const Knot* knots, uint8_t count, uint8_t* out);
size_t encode_stop(uint8_t* out);
size_t encode_release(uint8_t* out);
/// Releases the channels whose bit is set in `mask` (mask_bytes = (channel count + 7) / 8).
size_t encode_release_channels(const uint8_t* mask, uint8_t mask_bytes, uint8_t* out);
size_t encode_query(uint8_t* out);
size_t encode_status(const Status& status, uint8_t* out);
/// 0 for more than kMaxChannels.
size_t encode_positions(const uint16_t* outputs, uint8_t count, uint8_t* out);

/// A knot's slope field for `units_per_second` output units per second: rounded to kSlopeUnit,
/// saturated to the field.
int16_t slope_field(int32_t units_per_second);

/// Finds frames in a byte stream one byte at a time: skips bytes until a start byte, checks the
/// length and the CRC, and on a bad frame looks for the next start byte after the one it tried.
/// Its buffer (the caller's) holds one frame; nothing allocated.
struct Parser {
  uint8_t* buffer;         ///< room for `room` bytes
  uint8_t room;            ///< the longest frame taken: a longer one counts as bad
  uint8_t held;            ///< bytes of the frame being read
  uint32_t bad_frames;     ///< CRC or length failures
  uint32_t skipped;        ///< bytes that started no frame
  uint8_t type;            ///< of the last complete frame
  uint8_t length;          ///< its payload's length
  const uint8_t* payload;  ///< into buffer: valid until the next push
};
/// Starts `parser` afresh on the caller's `buffer` of `room` bytes, kOverhead to kMaxFrame: the
/// longest frame it takes (a device that knows its longest message keeps a smaller buffer; a
/// longer frame is counted bad and skipped).
void parser_reset(Parser& parser, uint8_t* buffer, uint8_t room);
/// Takes one byte; true when it completes a good frame (type, length, payload set).
bool parser_push(Parser& parser, uint8_t byte);

/// Message readers: false when the payload is not that message's.
bool read_hello(const uint8_t* payload, uint8_t length, uint8_t& version);
bool read_time(const uint8_t* payload, uint8_t length, uint32_t& time_us);
/// The time and channel count of a knots payload whose length matches its count (the knots
/// unread: a device reads them straight into where it keeps them).
bool read_knots_header(const uint8_t* payload, uint8_t length, uint32_t& time_us, uint8_t& count);
/// Fills knots[0..count) (room for `capacity`): false for a count above it or a length that
/// does not match the count.
bool read_knots(const uint8_t* payload, uint8_t length, uint32_t& time_us, Knot* knots, uint8_t capacity, uint8_t& count);
bool read_status(const uint8_t* payload, uint8_t length, Status& status);
bool read_positions(const uint8_t* payload, uint8_t length, uint16_t* outputs, uint8_t capacity, uint8_t& count);

}  // namespace avar_device
}  // namespace firmware_iface
}  // namespace avar
