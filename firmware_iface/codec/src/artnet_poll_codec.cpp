#include "avar/firmware_iface/artnet_poll_codec.hpp"

#include <algorithm>

#include "avar/core/byte_order.hpp"

namespace avar::firmware_iface::artnet {
namespace {

template <std::size_t N>
void put_bytes(std::span<std::uint8_t> out, std::size_t at, const std::array<std::uint8_t, N>& bytes) noexcept {
  std::copy(bytes.begin(), bytes.end(), out.begin() + static_cast<std::ptrdiff_t>(at));
}

template <std::size_t N>
void get_bytes(std::span<const std::uint8_t> in, std::size_t at, std::array<std::uint8_t, N>& bytes) noexcept {
  if (at + N > in.size()) return;  // a short reply: the field stays zero
  std::copy_n(in.begin() + static_cast<std::ptrdiff_t>(at), N, bytes.begin());
}

template <std::size_t N>
void put_name(std::span<std::uint8_t> out, std::size_t at, const NameField<N>& name) noexcept {
  std::transform(name.chars.begin(), name.chars.end(), out.begin() + static_cast<std::ptrdiff_t>(at),
                 [](char c) { return static_cast<std::uint8_t>(c); });
  out[at + N - 1] = 0;  // always terminated
}

template <std::size_t N>
void get_name(std::span<const std::uint8_t> in, std::size_t at, NameField<N>& name) noexcept {
  std::transform(in.begin() + static_cast<std::ptrdiff_t>(at), in.begin() + static_cast<std::ptrdiff_t>(at + N),
                 name.chars.begin(), [](std::uint8_t c) { return static_cast<char>(c); });
  name.chars[N - 1] = '\0';  // a field sent without its NUL keeps N - 1 characters, as put_name sends
}

}  // namespace

std::size_t encode_poll(std::span<std::uint8_t> out, const Poll& poll) noexcept {
  if (out.size() < kPollSize) return 0;
  write_header(OpCode::poll, true, out);
  out[12] = poll.flags;
  out[13] = poll.diag_priority;
  put_u16_be(&out[14], poll.target_top);
  put_u16_be(&out[16], poll.target_bottom);
  put_u16_be(&out[18], poll.esta_manufacturer);
  put_u16_be(&out[20], poll.oem);
  return kPollSize;
}

std::optional<Poll> decode_poll(std::span<const std::uint8_t> datagram) noexcept {
  if (read_opcode(datagram) != static_cast<std::uint16_t>(OpCode::poll) || datagram.size() < kMinPollSize ||
      !supported_version(datagram))
    return std::nullopt;
  Poll p;
  p.flags = datagram[12];
  p.diag_priority = datagram[13];
  if (datagram.size() >= 18) {
    p.target_top = get_u16_be(&datagram[14]);
    p.target_bottom = get_u16_be(&datagram[16]);
  }
  if (datagram.size() >= kPollSize) {
    p.esta_manufacturer = get_u16_be(&datagram[18]);
    p.oem = get_u16_be(&datagram[20]);
  }
  return p;
}

std::size_t encode_poll_reply(std::span<std::uint8_t> out, const PollReply& r) noexcept {
  if (out.size() < kPollReplySize || r.num_ports > 4) return 0;
  std::fill_n(out.begin(), kPollReplySize, std::uint8_t{0});
  write_header(OpCode::poll_reply, false, out);
  put_bytes(out, 10, r.ip);
  put_u16_le(&out[14], r.port);  // the one little-endian field
  put_u16_be(&out[16], r.version_info);
  out[18] = r.net_switch;
  out[19] = r.sub_switch;
  put_u16_be(&out[20], r.oem);
  out[22] = r.ubea_version;
  out[23] = r.status1;
  put_u16_le(&out[24], r.esta_manufacturer);  // EstaManLo first
  put_name(out, 26, r.short_name);
  put_name(out, 44, r.long_name);
  put_name(out, 108, r.node_report);
  put_u16_be(&out[172], r.num_ports);
  put_bytes(out, 174, r.port_types);
  put_bytes(out, 178, r.good_input);
  put_bytes(out, 182, r.good_output_a);
  put_bytes(out, 186, r.sw_in);
  put_bytes(out, 190, r.sw_out);
  out[194] = r.acn_priority;
  out[195] = r.sw_macro;
  out[196] = r.sw_remote;
  out[200] = r.style;
  put_bytes(out, 201, r.mac);
  put_bytes(out, 207, r.bind_ip);
  out[211] = r.bind_index;
  out[212] = r.status2;
  put_bytes(out, 213, r.good_output_b);
  out[217] = r.status3;
  return kPollReplySize;
}

std::optional<PollReply> decode_poll_reply(std::span<const std::uint8_t> d) noexcept {
  if (read_opcode(d) != static_cast<std::uint16_t>(OpCode::poll_reply) || d.size() < kMinPollReplySize) return std::nullopt;
  PollReply r;
  r.num_ports = get_u16_be(&d[172]);
  if (r.num_ports > 4) return std::nullopt;
  get_bytes(d, 10, r.ip);
  r.port = get_u16_le(&d[14]);
  r.version_info = get_u16_be(&d[16]);
  r.net_switch = d[18];
  r.sub_switch = d[19];
  r.oem = get_u16_be(&d[20]);
  r.ubea_version = d[22];
  r.status1 = d[23];
  r.esta_manufacturer = get_u16_le(&d[24]);
  get_name(d, 26, r.short_name);
  get_name(d, 44, r.long_name);
  get_name(d, 108, r.node_report);
  get_bytes(d, 174, r.port_types);
  get_bytes(d, 178, r.good_input);
  get_bytes(d, 182, r.good_output_a);
  get_bytes(d, 186, r.sw_in);
  get_bytes(d, 190, r.sw_out);
  r.acn_priority = d[194];
  r.sw_macro = d[195];
  r.sw_remote = d[196];
  r.style = d[200];
  get_bytes(d, 201, r.mac);
  get_bytes(d, 207, r.bind_ip);
  if (d.size() > 211) r.bind_index = d[211];
  if (d.size() > 212) r.status2 = d[212];
  get_bytes(d, 213, r.good_output_b);
  if (d.size() > 217) r.status3 = d[217];
  return r;
}

}  // namespace avar::firmware_iface::artnet
