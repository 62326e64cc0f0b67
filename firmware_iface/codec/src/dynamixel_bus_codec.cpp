#include "avar/firmware_iface/dynamixel_bus_codec.hpp"

#include "avar/firmware_iface/dynamixel_codec.hpp"

namespace avar::firmware_iface {
namespace dxl = dynamixel;
namespace {

constexpr std::size_t kHeader = 7;  // FF FF FD 00 ID LEN_L LEN_H

}  // namespace

Framing DynamixelBusCodec::parse(std::span<const std::uint8_t> in, BusReply* reply, std::size_t* used,
                                 std::size_t* want) noexcept {
  *used = 0;
  if (!in.empty()) {
    dxl::Status status;
    switch (dxl::decode_status(in, scratch_, &status, used)) {
      case dxl::DecodeResult::ok:
        reply->device = status.id;
        reply->error = status.error;
        reply->device_error = (status.error & 0x7F) != 0;
        reply->params = status.params;
        return Framing::reply;
      case dxl::DecodeResult::bad_crc: return Framing::bad_checksum;
      case dxl::DecodeResult::bad_framing: return Framing::stray;
      case dxl::DecodeResult::not_status: return Framing::ignored;
      case dxl::DecodeResult::need_more: break;
    }
  }
  *used = 0;
  if (in.size() < kHeader) {
    *want = kHeader - in.size();
    return Framing::need_more;
  }
  const std::size_t need = kHeader + dxl::read_u16(in.subspan(5, 2));
  if (need <= in.size() || need > kMaxPacket) {
    // A length no reply of ours can have: drop a byte and look for the next header.
    *used = 1;
    return Framing::stray;
  }
  *want = need - in.size();
  return Framing::need_more;
}

std::size_t DynamixelBusCodec::encode_retry(std::uint32_t device, std::span<std::uint8_t> out) noexcept {
  return dxl::encode_read(out, static_cast<std::uint8_t>(device), retry_address_, retry_length_);
}

}  // namespace avar::firmware_iface
