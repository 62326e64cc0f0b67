#include "avar/inputs/artnet_timecode_codec.hpp"

#include "avar/firmware_iface/artnet_header.hpp"
#include "avar/inputs/timecode_fix.hpp"

namespace avar::inputs::artnet {

using firmware_iface::artnet::OpCode;
using firmware_iface::artnet::read_opcode;
using firmware_iface::artnet::supported_version;
using firmware_iface::artnet::write_header;

const char* to_string(TimeCodeVerdict v) noexcept {
  switch (v) {
    case TimeCodeVerdict::ok: return "ok";
    case TimeCodeVerdict::not_artnet: return "not Art-Net";
    case TimeCodeVerdict::other_opcode: return "another Art-Net packet";
    case TimeCodeVerdict::old_version: return "protocol version below 14";
    case TimeCodeVerdict::too_short: return "ArtTimeCode shorter than 19 bytes";
    case TimeCodeVerdict::bad_type: return "timecode type above 3";
    case TimeCodeVerdict::out_of_range: return "timecode field out of range";
  }
  return "?";
}

std::size_t encode_timecode(const Timecode& t, std::uint8_t stream_id, std::span<std::uint8_t> out) noexcept {
  if (out.size() < kTimeCodeSize || write_header(OpCode::time_code, true, out) == 0) return 0;
  out[12] = 0;  // Filler1
  out[13] = stream_id;
  out[14] = static_cast<std::uint8_t>(t.frames);
  out[15] = static_cast<std::uint8_t>(t.seconds);
  out[16] = static_cast<std::uint8_t>(t.minutes);
  out[17] = static_cast<std::uint8_t>(t.hours);
  out[18] = static_cast<std::uint8_t>(timecode_rate_code(t.rate));
  return kTimeCodeSize;
}

TimeCodeVerdict decode_timecode(std::span<const std::uint8_t> datagram, Timecode& t, std::uint8_t* stream_id) noexcept {
  const auto op = read_opcode(datagram);
  if (!op) return TimeCodeVerdict::not_artnet;
  if (*op != static_cast<std::uint16_t>(OpCode::time_code)) return TimeCodeVerdict::other_opcode;
  if (datagram.size() < kTimeCodeSize) return TimeCodeVerdict::too_short;
  if (!supported_version(datagram)) return TimeCodeVerdict::old_version;
  if (datagram[18] > 3) return TimeCodeVerdict::bad_type;
  const Timecode decoded{datagram[17], datagram[16], datagram[15], datagram[14], timecode_rate_from_code(datagram[18])};
  if (!valid(decoded)) return TimeCodeVerdict::out_of_range;
  t = decoded;
  if (stream_id) *stream_id = datagram[13];
  return TimeCodeVerdict::ok;
}

}  // namespace avar::inputs::artnet
