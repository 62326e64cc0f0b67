#include "avar/firmware_iface/avar_device_codec.hpp"

namespace avar {
namespace firmware_iface {
namespace avar_device {
namespace {

/// Bytes of one channel's knot and of one output in a frame (size_t: offsets into payloads).
const size_t kKnotSize = 4, kOutputSize = 2;

void put16(uint8_t* at, uint16_t v) {
  at[0] = static_cast<uint8_t>(v);
  at[1] = static_cast<uint8_t>(v >> 8);
}
void put32(uint8_t* at, uint32_t v) {
  for (unsigned i = 0; i < 4; ++i) at[i] = static_cast<uint8_t>(v >> (8 * i));
}
uint16_t get16(const uint8_t* at) { return static_cast<uint16_t>(at[0] | (static_cast<uint16_t>(at[1]) << 8)); }
uint32_t get32(const uint8_t* at) {
  uint32_t v = 0;
  for (unsigned i = 0; i < 4; ++i) v |= static_cast<uint32_t>(at[i]) << (8 * i);
  return v;
}
/// Two's complement of a 16-bit field, without relying on implementation-defined conversions.
int16_t as_signed16(uint16_t v) {
  return v < 0x8000u ? static_cast<int16_t>(v) : static_cast<int16_t>(-static_cast<int32_t>(0x10000u - v));
}

}  // namespace

uint16_t crc16(uint16_t crc, const uint8_t* bytes, size_t length) {
  for (size_t i = 0; i < length; ++i) {
    crc = static_cast<uint16_t>(crc ^ (static_cast<uint16_t>(bytes[i]) << 8));
    for (unsigned bit = 0; bit < 8; ++bit)
      crc = (crc & 0x8000u) ? static_cast<uint16_t>((crc << 1) ^ 0x1021u) : static_cast<uint16_t>(crc << 1);
  }
  return crc;
}

size_t encode_frame(uint8_t type, const uint8_t* payload, uint8_t length, uint8_t* out) {
  if (length > kMaxPayload) return 0;
  out[0] = kStart;
  out[1] = type;
  out[2] = length;
  for (uint8_t i = 0; i < length; ++i) out[3 + i] = payload[i];
  put16(out + 3 + length, crc16(0xffffu, out + 1, 2u + length));
  return kOverhead + length;
}

size_t encode_hello(uint8_t* out) {
  const uint8_t version = kVersion;
  return encode_frame(kHello, &version, 1, out);
}

size_t encode_time(uint32_t time_us, uint8_t* out) {
  uint8_t payload[4];
  put32(payload, time_us);
  return encode_frame(kTime, payload, 4, out);
}

size_t encode_knots(uint32_t time_us, const Knot* knots, uint8_t count, uint8_t* out) {
  if (count == 0 || count > kMaxChannels) return 0;
  uint8_t payload[kMaxPayload];
  put32(payload, time_us);
  payload[4] = count;
  for (uint8_t c = 0; c < count; ++c) {
    put16(payload + 5 + kKnotSize * c, knots[c].value);
    put16(payload + 7 + kKnotSize * c, static_cast<uint16_t>(knots[c].slope));
  }
  return encode_frame(kKnots, payload, static_cast<uint8_t>(5 + 4 * count), out);
}

size_t encode_stop(uint8_t* out) { return encode_frame(kStop, nullptr, 0, out); }
size_t encode_release(uint8_t* out) { return encode_frame(kRelease, nullptr, 0, out); }
size_t encode_release_channels(const uint8_t* mask, uint8_t mask_bytes, uint8_t* out) {
  return encode_frame(kRelease, mask, mask_bytes, out);
}
size_t encode_query(uint8_t* out) { return encode_frame(kQuery, nullptr, 0, out); }

size_t encode_status(const Status& s, uint8_t* out) {
  uint8_t payload[kStatusSize];
  payload[0] = s.version;
  payload[1] = s.channel_count;
  put16(payload + 2, s.rate_hz);
  payload[4] = s.knot_capacity;
  payload[5] = s.state;
  put16(payload + 6, s.bad_frames);
  put32(payload + 8, s.time_us);
  return encode_frame(kStatus, payload, kStatusSize, out);
}

size_t encode_positions(const uint16_t* outputs, uint8_t count, uint8_t* out) {
  if (count > kMaxChannels) return 0;
  uint8_t payload[kMaxPayload];
  payload[0] = count;
  for (uint8_t c = 0; c < count; ++c) put16(payload + 1 + kOutputSize * c, outputs[c]);
  return encode_frame(kPositions, payload, static_cast<uint8_t>(1 + 2 * count), out);
}

int16_t slope_field(int32_t units_per_second) {
  // Rounded half away from zero, in steps of kSlopeUnit.
  const int32_t half = kSlopeUnit / 2;
  const int32_t steps =
      units_per_second >= 0 ? (units_per_second + half) / kSlopeUnit : -((half - units_per_second) / kSlopeUnit);
  if (steps > 32767) return 32767;
  if (steps < -32768) return -32768;
  return static_cast<int16_t>(steps);
}

void parser_reset(Parser& p, uint8_t* buffer, uint8_t room) {
  p.buffer = buffer;
  p.room = room < kOverhead ? static_cast<uint8_t>(kOverhead) : room;
  p.held = 0;
  p.bad_frames = 0;
  p.skipped = 0;
  p.type = 0;
  p.length = 0;
  p.payload = p.buffer + 3;
}

namespace {

/// Drops the frame held (a bad one) and looks for a start byte among the bytes after its own.
void resync(Parser& p) {
  uint8_t from = 1;
  while (from < p.held && p.buffer[from] != kStart) ++from;
  p.skipped += from;
  const uint8_t keep = static_cast<uint8_t>(p.held - from);
  for (uint8_t i = 0; i < keep; ++i) p.buffer[i] = p.buffer[from + i];
  p.held = keep;
}

/// Whether the bytes held start a frame that may still be good: false for a bad length (or one
/// longer than the buffer's room); a
/// complete frame's CRC is checked by the caller.
bool plausible(const Parser& p) { return p.held < 3 || (p.buffer[2] <= kMaxPayload && kOverhead + p.buffer[2] <= p.room); }

}  // namespace

bool parser_push(Parser& p, uint8_t byte) {
  if (p.held == 0 && byte != kStart) {
    ++p.skipped;
    return false;
  }
  p.buffer[p.held++] = byte;
  // A bad frame's bytes may hold the start of the next one: re-examine them until what is held is
  // a plausible beginning, or a good frame.
  for (;;) {
    if (p.held == 0) return false;
    if (!plausible(p)) {
      ++p.bad_frames;
      resync(p);
      continue;
    }
    if (p.held < 3) return false;
    const size_t total = kOverhead + p.buffer[2];
    if (p.held < total) return false;
    const uint8_t length = p.buffer[2];
    if (crc16(0xffffu, p.buffer + 1, 2u + length) == get16(p.buffer + 3 + length)) {
      p.type = p.buffer[1];
      p.length = length;
      p.payload = p.buffer + 3;
      p.held = 0;
      return true;
    }
    ++p.bad_frames;
    resync(p);
  }
}

bool read_hello(const uint8_t* payload, uint8_t length, uint8_t& version) {
  if (length != 1) return false;
  version = payload[0];
  return true;
}

bool read_time(const uint8_t* payload, uint8_t length, uint32_t& time_us) {
  if (length != 4) return false;
  time_us = get32(payload);
  return true;
}

bool read_knots_header(const uint8_t* payload, uint8_t length, uint32_t& time_us, uint8_t& count) {
  if (length < 5) return false;
  const uint8_t n = payload[4];
  if (n == 0 || length != 5 + kKnotSize * n) return false;
  time_us = get32(payload);
  count = n;
  return true;
}

bool read_knots(const uint8_t* payload, uint8_t length, uint32_t& time_us, Knot* knots, uint8_t capacity, uint8_t& count) {
  uint8_t n = 0;
  if (!read_knots_header(payload, length, time_us, n) || n > capacity) return false;
  for (uint8_t c = 0; c < n; ++c) {
    knots[c].value = get16(payload + 5 + kKnotSize * c);
    knots[c].slope = as_signed16(get16(payload + 7 + kKnotSize * c));
  }
  count = n;
  return true;
}

bool read_status(const uint8_t* payload, uint8_t length, Status& s) {
  if (length != kStatusSize) return false;
  s.version = payload[0];
  s.channel_count = payload[1];
  s.rate_hz = get16(payload + 2);
  s.knot_capacity = payload[4];
  s.state = payload[5];
  s.bad_frames = get16(payload + 6);
  s.time_us = get32(payload + 8);
  return true;
}

bool read_positions(const uint8_t* payload, uint8_t length, uint16_t* outputs, uint8_t capacity, uint8_t& count) {
  if (length < 1) return false;
  const uint8_t n = payload[0];
  if (n > capacity || length != 1 + 2 * n) return false;
  for (uint8_t c = 0; c < n; ++c) outputs[c] = get16(payload + 1 + kOutputSize * c);
  count = n;
  return true;
}

}  // namespace avar_device
}  // namespace firmware_iface
}  // namespace avar
