#include "avar/firmware_iface/dynamixel_codec.hpp"

#include <array>

#include "avar/core/byte_order.hpp"

namespace avar::firmware_iface::dynamixel {
namespace {

constexpr std::array<std::uint16_t, 256> make_crc_table() {
  std::array<std::uint16_t, 256> table{};
  for (unsigned i = 0; i < 256; ++i) {
    unsigned c = i << 8;
    for (int bit = 0; bit < 8; ++bit) c = (c & 0x8000) ? ((c << 1) ^ 0x8005) : (c << 1);
    table[i] = static_cast<std::uint16_t>(c & 0xFFFF);
  }
  return table;
}
constexpr std::array<std::uint16_t, 256> kCrcTable = make_crc_table();

constexpr std::size_t kHeaderSize = 7;  // FF FF FD 00 ID LEN_L LEN_H

/// Appends b, inserting a stuffing 0xFD after every FF FF FD seen in the stuffed region
/// (which starts at `region`).
bool put_stuffed(std::span<std::uint8_t> out, std::size_t region, std::size_t& n, std::uint8_t b) {
  if (n >= out.size()) return false;
  out[n++] = b;
  if (b == 0xFD && n - region >= 3 && out[n - 2] == 0xFF && out[n - 3] == 0xFF) {
    if (n >= out.size()) return false;
    out[n++] = 0xFD;
  }
  return true;
}

}  // namespace

std::uint16_t crc16(std::span<const std::uint8_t> bytes) noexcept {
  std::uint16_t crc = 0;
  for (std::uint8_t b : bytes) crc = static_cast<std::uint16_t>((crc << 8) ^ kCrcTable[((crc >> 8) ^ b) & 0xFF]);
  return crc;
}

std::size_t encode_instruction(std::span<std::uint8_t> out, std::uint8_t id, std::uint8_t instruction,
                               std::span<const std::uint8_t> params) noexcept {
  if ((id > kMaxId && id != kBroadcastId) || out.size() < kHeaderSize + 1 + 2) return 0;
  out[0] = 0xFF, out[1] = 0xFF, out[2] = 0xFD, out[3] = 0x00, out[4] = id;
  std::size_t n = kHeaderSize;
  // The stuffed region is the instruction and its parameters.
  if (!put_stuffed(out, kHeaderSize, n, instruction)) return 0;
  for (std::uint8_t b : params)
    if (!put_stuffed(out, kHeaderSize, n, b)) return 0;
  const std::size_t length = n - kHeaderSize + 2;  // instruction + parameters (stuffed) + CRC
  if (length > 0xFFFF || n + 2 > out.size()) return 0;
  put_u16_le(&out[5], static_cast<std::uint16_t>(length));
  put_u16_le(&out[n], crc16(out.first(n)));
  return n + 2;
}

std::size_t encode_ping(std::span<std::uint8_t> out, std::uint8_t id) noexcept { return encode_instruction(out, id, kPing, {}); }

std::size_t encode_read(std::span<std::uint8_t> out, std::uint8_t id, std::uint16_t address, std::uint16_t length) noexcept {
  std::uint8_t p[4];
  put_u16_le(p, address);
  put_u16_le(p + 2, length);
  return encode_instruction(out, id, kRead, p);
}

std::size_t encode_write(std::span<std::uint8_t> out, std::uint8_t id, std::uint16_t address,
                         std::span<const std::uint8_t> data) noexcept {
  std::array<std::uint8_t, 2 + 256> p{};
  if (data.size() > 256) return 0;
  put_u16_le(p.data(), address);
  std::copy(data.begin(), data.end(), p.begin() + 2);
  return encode_instruction(out, id, kWrite, std::span(p.data(), 2 + data.size()));
}

std::size_t encode_action(std::span<std::uint8_t> out, std::uint8_t id) noexcept {
  return encode_instruction(out, id, kAction, {});
}
std::size_t encode_reboot(std::span<std::uint8_t> out, std::uint8_t id) noexcept {
  return encode_instruction(out, id, kReboot, {});
}

std::size_t encode_factory_reset(std::span<std::uint8_t> out, std::uint8_t id, std::uint8_t mode) noexcept {
  if (mode != 0xFF && mode != 0x01 && mode != 0x02) return 0;
  const std::uint8_t p[1] = {mode};
  return encode_instruction(out, id, kFactoryReset, p);
}

std::size_t encode_sync_read(std::span<std::uint8_t> out, std::uint16_t address, std::uint16_t length,
                             std::span<const std::uint8_t> ids) noexcept {
  std::array<std::uint8_t, 4 + kMaxId + 1> p{};
  if (ids.empty() || ids.size() > kMaxId + 1) return 0;
  put_u16_le(p.data(), address);
  put_u16_le(p.data() + 2, length);
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (ids[i] > kMaxId) return 0;
    p[4 + i] = ids[i];
  }
  return encode_instruction(out, kBroadcastId, kSyncRead, std::span(p.data(), 4 + ids.size()));
}

std::size_t encode_sync_write_u32(std::span<std::uint8_t> out, std::uint16_t address, std::span<const std::uint8_t> ids,
                                  std::span<const std::int32_t> values) noexcept {
  std::array<std::uint8_t, 4 + 5 * (kMaxId + 1)> p{};
  if (ids.empty() || ids.size() != values.size() || ids.size() > kMaxId + 1) return 0;
  put_u16_le(p.data(), address);
  put_u16_le(p.data() + 2, 4);
  std::size_t n = 4;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (ids[i] > kMaxId) return 0;
    const auto v = static_cast<std::uint32_t>(values[i]);
    p[n++] = ids[i];
    for (int byte = 0; byte < 4; ++byte) p[n++] = static_cast<std::uint8_t>(v >> (8 * byte));
  }
  return encode_instruction(out, kBroadcastId, kSyncWrite, std::span(p.data(), n));
}

DecodeResult decode_packet(std::span<const std::uint8_t> in, std::span<std::uint8_t> scratch, Packet* packet,
                           std::size_t* consumed) noexcept {
  *consumed = 0;
  // Find a header FF FF FD 00 (a stuffed FF FF FD FD inside a packet is not one).
  std::size_t start = 0;
  while (start + 4 <= in.size() &&
         !(in[start] == 0xFF && in[start + 1] == 0xFF && in[start + 2] == 0xFD && in[start + 3] == 0x00))
    ++start;
  if (start + 4 > in.size()) {
    // Keep a possible header prefix at the end; drop the rest.
    std::size_t keep = 0;
    for (std::size_t k = std::min<std::size_t>(3, in.size()); k > 0; --k) {
      const std::uint8_t prefix[3] = {0xFF, 0xFF, 0xFD};
      if (std::equal(in.end() - static_cast<long>(k), in.end(), prefix)) {
        keep = k;
        break;
      }
    }
    *consumed = in.size() - keep;
    return *consumed > 0 ? DecodeResult::bad_framing : DecodeResult::need_more;
  }
  if (start > 0) {
    *consumed = start;
    return DecodeResult::bad_framing;
  }
  if (in.size() < kHeaderSize) return DecodeResult::need_more;
  const std::size_t length = read_u16(in.subspan(5, 2));
  if (length < 3 || in[4] == 0xFD || in[4] == 0xFF) {
    *consumed = 1;
    return DecodeResult::bad_framing;
  }
  const std::size_t total = kHeaderSize + length;
  if (in.size() < total) return DecodeResult::need_more;
  *consumed = total;
  const std::uint16_t crc = read_u16(in.subspan(total - 2, 2));
  if (crc != crc16(in.first(total - 2))) return DecodeResult::bad_crc;
  // Unstuff the parameters (after the instruction byte) into scratch: the stuffed region starts
  // at the instruction, so an FD following FF FF FD inside it is a stuffing byte.
  std::size_t n = 0;
  const std::size_t first = kHeaderSize + 1, end = total - 2;
  for (std::size_t i = first; i < end; ++i) {
    if (n >= scratch.size()) return DecodeResult::bad_framing;
    scratch[n++] = in[i];
    if (in[i] == 0xFD && i + 1 < end && in[i + 1] == 0xFD && i >= kHeaderSize + 2 && in[i - 1] == 0xFF && in[i - 2] == 0xFF) ++i;
  }
  packet->id = in[4];
  packet->instruction = in[kHeaderSize];
  packet->params = scratch.first(n);
  return DecodeResult::ok;
}

DecodeResult decode_status(std::span<const std::uint8_t> in, std::span<std::uint8_t> scratch, Status* status,
                           std::size_t* consumed) noexcept {
  Packet packet;
  const DecodeResult r = decode_packet(in, scratch, &packet, consumed);
  if (r != DecodeResult::ok) return r;
  if (packet.instruction != kStatus || packet.params.empty()) return DecodeResult::not_status;
  status->id = packet.id;
  status->error = packet.params[0];
  status->params = packet.params.subspan(1);
  return DecodeResult::ok;
}

std::string describe_processing_error(std::uint8_t error) {
  switch (error & 0x7F) {
    case 0: return "none";
    case 1: return "result fail";
    case 2: return "instruction error";
    case 3: return "CRC error";
    case 4: return "data range error";
    case 5: return "data length error";
    case 6: return "data limit error";
    case 7: return "access error";
    default: return "processing error " + std::to_string(error & 0x7F);
  }
}

std::string describe_hardware_error(std::uint8_t bits) {
  static constexpr std::pair<std::uint8_t, const char*> kBits[] = {{0x01, "input voltage error"},
                                                                   {0x04, "overheating"},
                                                                   {0x08, "motor encoder error"},
                                                                   {0x10, "electrical shock error"},
                                                                   {0x20, "overload error"}};
  std::string out;
  for (const auto& [bit, name] : kBits)
    if (bits & bit) out += (out.empty() ? "" : ", ") + std::string(name);
  return out.empty() ? "none" : out;
}

}  // namespace avar::firmware_iface::dynamixel
