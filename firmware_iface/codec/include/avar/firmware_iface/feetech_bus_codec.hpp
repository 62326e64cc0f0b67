#pragma once
// Feetech SCS/STS status packets for BusExchange: replies framed by feetech::decode_packet, and
// a plain Read of the registers the exchange asked for as the retry. Real-time safe.

#include <cstdint>

#include "avar/firmware_iface/bus_codec.hpp"

namespace avar::firmware_iface {

class FeetechBusCodec final : public RegisterBusCodec {
 public:
  Framing parse(std::span<const std::uint8_t> in, BusReply* reply, std::size_t* used, std::size_t* want) noexcept override;
  std::size_t encode_retry(std::uint32_t device, std::span<std::uint8_t> out) noexcept override;
};

}  // namespace avar::firmware_iface
