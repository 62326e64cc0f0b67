#include "avar/firmware_iface/feetech_codec.hpp"

#include <algorithm>
#include <array>
#include <cstdlib>

#include "avar/core/byte_order.hpp"

namespace avar::firmware_iface::feetech {

std::uint16_t to_sign_magnitude(int value, int sign_bit) noexcept {
  const int max = (1 << sign_bit) - 1;
  const int magnitude = std::min(std::abs(std::max(value, -max)), max);
  return static_cast<std::uint16_t>(magnitude | (value < 0 ? 1 << sign_bit : 0));
}

int from_sign_magnitude(std::uint16_t raw, int sign_bit) noexcept {
  const int magnitude = raw & ((1 << sign_bit) - 1);
  return (raw >> sign_bit) & 1 ? -magnitude : magnitude;
}

std::uint16_t position_word(Series series, long steps) noexcept {
  if (series == Series::sts) return to_sign_magnitude(static_cast<int>(std::clamp(steps, -32767L, 32767L)), kPositionSignBit);
  return static_cast<std::uint16_t>(std::clamp(steps, 0L, 65535L));
}

int position_from_word(Series series, std::uint16_t raw) noexcept {
  return series == Series::sts ? from_sign_magnitude(raw, kPositionSignBit) : raw;
}

void put_word(Series series, std::span<std::uint8_t, 2> out, std::uint16_t value) noexcept {
  if (series == Series::sts) put_u16_le(out.data(), value);
  else put_u16_be(out.data(), value);
}

std::uint16_t get_word(Series series, std::span<const std::uint8_t> in) noexcept {
  return series == Series::sts ? get_u16_le(in.data()) : get_u16_be(in.data());
}

std::uint8_t checksum(std::span<const std::uint8_t> bytes) noexcept {
  unsigned sum = 0;
  for (std::uint8_t b : bytes) sum += b;
  return static_cast<std::uint8_t>(~sum & 0xFF);
}

std::size_t encode_packet(std::span<std::uint8_t> out, std::uint8_t id, std::uint8_t code,
                          std::span<const std::uint8_t> params) noexcept {
  const std::size_t total = kMinPacketSize + params.size();
  if (id > kBroadcastId || total > kMaxPacketSize || out.size() < total) return 0;
  out[0] = 0xFF, out[1] = 0xFF, out[2] = id;
  out[3] = static_cast<std::uint8_t>(params.size() + 2);
  out[4] = code;
  std::copy(params.begin(), params.end(), out.begin() + 5);
  out[total - 1] = checksum(out.subspan(2, total - 3));
  return total;
}

std::size_t encode_ping(std::span<std::uint8_t> out, std::uint8_t id) noexcept { return encode_packet(out, id, kPing, {}); }

std::size_t encode_read(std::span<std::uint8_t> out, std::uint8_t id, std::uint8_t address, std::uint8_t length) noexcept {
  if (id == kBroadcastId || length == 0) return 0;
  const std::uint8_t p[2] = {address, length};
  return encode_packet(out, id, kRead, p);
}

std::size_t encode_write(std::span<std::uint8_t> out, std::uint8_t id, std::uint8_t address,
                         std::span<const std::uint8_t> data) noexcept {
  std::array<std::uint8_t, 1 + 252> p{};
  if (data.empty() || data.size() > p.size() - 1) return 0;
  p[0] = address;
  std::copy(data.begin(), data.end(), p.begin() + 1);
  return encode_packet(out, id, kWrite, std::span(p.data(), 1 + data.size()));
}

std::size_t encode_write_word(std::span<std::uint8_t> out, Series series, std::uint8_t id, std::uint8_t address,
                              std::uint16_t value) noexcept {
  std::array<std::uint8_t, 2> data{};
  put_word(series, data, value);
  return encode_write(out, id, address, data);
}

std::size_t encode_sync_write(std::span<std::uint8_t> out, std::uint8_t address, std::uint8_t length,
                              std::span<const std::uint8_t> ids, std::span<const std::uint8_t> data) noexcept {
  std::array<std::uint8_t, 253> p{};
  const std::size_t n = 2 + (length + std::size_t{1}) * ids.size();
  if (ids.empty() || length == 0 || data.size() != length * ids.size() || n > p.size()) return 0;
  p[0] = address, p[1] = length;
  std::size_t at = 2;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (ids[i] > kMaxId) return 0;
    p[at++] = ids[i];
    const auto block = data.subspan(i * length, length);
    std::copy(block.begin(), block.end(), p.begin() + static_cast<long>(at));
    at += length;
  }
  return encode_packet(out, kBroadcastId, kSyncWrite, std::span(p.data(), n));
}

std::size_t encode_sync_write_words(std::span<std::uint8_t> out, Series series, std::uint8_t address,
                                    std::span<const std::uint8_t> ids, std::span<const std::uint16_t> values) noexcept {
  std::array<std::uint8_t, std::size_t{2} * 84> data{};  // 84 servos fill the largest packet
  if (ids.size() != values.size() || 2 * values.size() > data.size()) return 0;
  for (std::size_t i = 0; i < values.size(); ++i) put_word(series, std::span<std::uint8_t, 2>(&data[2 * i], 2), values[i]);
  return encode_sync_write(out, address, 2, ids, std::span(data.data(), 2 * values.size()));
}

std::size_t encode_sync_read(std::span<std::uint8_t> out, std::uint8_t address, std::uint8_t length,
                             std::span<const std::uint8_t> ids) noexcept {
  std::array<std::uint8_t, 253> p{};
  if (ids.empty() || length == 0 || 2 + ids.size() > p.size()) return 0;
  p[0] = address, p[1] = length;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (ids[i] > kMaxId) return 0;
    p[2 + i] = ids[i];
  }
  return encode_packet(out, kBroadcastId, kSyncRead, std::span(p.data(), 2 + ids.size()));
}

DecodeResult decode_packet(std::span<const std::uint8_t> in, Packet* packet, std::size_t* consumed) noexcept {
  *consumed = 0;
  std::size_t start = 0;
  while (start + 1 < in.size() && !(in[start] == 0xFF && in[start + 1] == 0xFF)) ++start;
  if (start + 1 >= in.size()) {
    // No header: drop everything but a trailing FF that may begin one.
    const std::size_t keep = !in.empty() && in.back() == 0xFF ? 1 : 0;
    *consumed = in.size() - keep;
    return *consumed > 0 ? DecodeResult::bad_framing : DecodeResult::need_more;
  }
  if (start > 0) {
    *consumed = start;
    return DecodeResult::bad_framing;
  }
  if (in.size() < kHeaderSize) return DecodeResult::need_more;
  // FF FF FF: the first FF is noise (an ID is never 0xFF).
  if (in[2] == 0xFF || in[3] < 2) {
    *consumed = 1;
    return DecodeResult::bad_framing;
  }
  const std::size_t total = kHeaderSize + in[3];
  if (in.size() < total) return DecodeResult::need_more;
  *consumed = total;
  if (in[total - 1] != checksum(in.subspan(2, total - 3))) return DecodeResult::bad_checksum;
  packet->id = in[2];
  packet->code = in[4];
  packet->params = in.subspan(5, total - kMinPacketSize);
  return DecodeResult::ok;
}

std::string describe_error(std::uint8_t error) {
  static constexpr std::pair<std::uint8_t, const char*> kBits[] = {
      {kErrorVoltage, "input voltage"},   {kErrorAngleSensor, "angle sensor"},
      {kErrorOverheat, "overheat"},       {kErrorOverCurrent, "over-current or range"},
      {kErrorChecksum, "checksum"},       {kErrorOverload, "overload"},
      {kErrorInstruction, "instruction"}, {0x80, "bit 7"}};
  std::string out;
  for (const auto& [bit, name] : kBits)
    if (error & bit) out += (out.empty() ? "" : ", ") + std::string(name);
  return out.empty() ? "none" : out;
}

}  // namespace avar::firmware_iface::feetech
