#include "avar/firmware_iface/dmx_codec.hpp"

#include <algorithm>
#include <array>

#include "avar/core/byte_order.hpp"

namespace avar::firmware_iface::dmx {

std::size_t encode_message(std::span<std::uint8_t> out, std::uint8_t label, std::span<const std::uint8_t> data) noexcept {
  const std::size_t total = kOverhead + data.size();
  if (data.size() > kMaxData || out.size() < total) return 0;
  out[0] = kStartOfMessage;
  out[1] = label;
  put_u16_le(&out[2], static_cast<std::uint16_t>(data.size()));
  std::copy(data.begin(), data.end(), out.begin() + 4);
  out[total - 1] = kEndOfMessage;
  return total;
}

std::size_t encode_send_dmx(std::span<std::uint8_t> out, std::span<const std::uint8_t> slots, std::uint8_t start_code) noexcept {
  const std::size_t n = std::max(slots.size(), kMinSlots);
  const std::size_t total = send_dmx_size(slots.size());
  if (slots.size() > kUniverseSize || out.size() < total) return 0;
  // Written in place (no copy of the universe through a temporary).
  out[0] = kStartOfMessage;
  out[1] = kOutputOnlySendDmx;
  put_u16_le(&out[2], static_cast<std::uint16_t>(n + 1));
  out[4] = start_code;
  std::copy(slots.begin(), slots.end(), out.begin() + 5);
  std::fill(out.begin() + 5 + static_cast<long>(slots.size()), out.begin() + 5 + static_cast<long>(n), std::uint8_t{0});
  out[total - 1] = kEndOfMessage;
  return total;
}

std::size_t encode_get_widget_parameters(std::span<std::uint8_t> out, std::uint16_t user_config_size) noexcept {
  if (user_config_size > 508) return 0;
  std::uint8_t data[2];
  put_u16_le(data, user_config_size);
  return encode_message(out, kGetWidgetParameters, data);
}

std::size_t encode_set_widget_parameters(std::span<std::uint8_t> out, const WidgetParameters& p) noexcept {
  if (p.break_time < 9 || p.break_time > 127 || p.mab_time < 1 || p.mab_time > 127 || p.output_rate > 40) return 0;
  const std::uint8_t data[5] = {0, 0, p.break_time, p.mab_time, p.output_rate};
  return encode_message(out, kSetWidgetParameters, data);
}

std::size_t encode_get_serial_number(std::span<std::uint8_t> out) noexcept { return encode_message(out, kGetSerialNumber, {}); }

std::size_t encode_widget_parameters_reply(std::span<std::uint8_t> out, const WidgetParameters& p,
                                           std::span<const std::uint8_t> user_config) noexcept {
  std::array<std::uint8_t, 5 + 508> data{};
  if (user_config.size() > 508) return 0;
  put_u16_le(&data[0], p.firmware);
  data[2] = p.break_time, data[3] = p.mab_time, data[4] = p.output_rate;
  std::copy(user_config.begin(), user_config.end(), data.begin() + 5);
  return encode_message(out, kGetWidgetParameters, std::span(data.data(), 5 + user_config.size()));
}

DecodeResult decode_message(std::span<const std::uint8_t> in, Message* message, std::size_t* consumed) noexcept {
  *consumed = 0;
  std::size_t start = 0;
  while (start < in.size() && in[start] != kStartOfMessage) ++start;
  if (start > 0) {
    *consumed = start;
    return DecodeResult::bad_framing;
  }
  if (in.size() < 4) return DecodeResult::need_more;
  const std::size_t length = get_u16_le(&in[2]);
  if (length > kMaxData) {
    *consumed = 1;
    return DecodeResult::bad_framing;
  }
  const std::size_t total = kOverhead + length;
  if (in.size() < total) return DecodeResult::need_more;
  if (in[total - 1] != kEndOfMessage) {
    *consumed = 1;
    return DecodeResult::bad_framing;
  }
  *consumed = total;
  message->label = in[1];
  message->data = in.subspan(4, length);
  return DecodeResult::ok;
}

bool decode_widget_parameters(std::span<const std::uint8_t> data, WidgetParameters* p) noexcept {
  if (data.size() < 5) return false;
  p->firmware = get_u16_le(&data[0]);
  p->break_time = data[2], p->mab_time = data[3], p->output_rate = data[4];
  return true;
}

}  // namespace avar::firmware_iface::dmx
