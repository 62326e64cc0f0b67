#include "avar/firmware_iface/feetech_bus_codec.hpp"

#include "avar/firmware_iface/feetech_codec.hpp"

namespace avar::firmware_iface {
namespace ft = feetech;

Framing FeetechBusCodec::parse(std::span<const std::uint8_t> in, BusReply* reply, std::size_t* used, std::size_t* want) noexcept {
  ft::Packet packet;
  switch (ft::decode_packet(in, &packet, used)) {
    case ft::DecodeResult::ok:
      reply->device = packet.id;
      reply->error = packet.code;
      reply->device_error = packet.code != 0;
      reply->params = packet.params;
      return Framing::reply;
    case ft::DecodeResult::bad_checksum: return Framing::bad_checksum;
    case ft::DecodeResult::bad_framing: return Framing::stray;
    case ft::DecodeResult::need_more: break;
  }
  // The rest of the packet under way, or its header.
  *used = 0;
  *want = in.size() >= ft::kHeaderSize ? ft::kHeaderSize + in[3] - in.size() : ft::kHeaderSize - in.size();
  return Framing::need_more;
}

std::size_t FeetechBusCodec::encode_retry(std::uint32_t device, std::span<std::uint8_t> out) noexcept {
  return ft::encode_read(out, static_cast<std::uint8_t>(device), static_cast<std::uint8_t>(retry_address_),
                         static_cast<std::uint8_t>(retry_length_));
}

}  // namespace avar::firmware_iface
