#pragma once
// DYNAMIXEL Protocol 2.0 status packets for BusExchange: replies framed by
// dynamixel::decode_status (echoes of our own requests ignored, impossible lengths skipped byte
// by byte), and a plain Read of the registers the exchange asked for as the retry. Real-time
// safe; the unstuffed parameters live in this codec's scratch until the next parse.

#include <array>
#include <cstdint>

#include "avar/firmware_iface/bus_codec.hpp"

namespace avar::firmware_iface {

class DynamixelBusCodec final : public RegisterBusCodec {
 public:
  /// Largest status packet this codec takes, bytes.
  static constexpr std::size_t kMaxPacket = 1024;

  Framing parse(std::span<const std::uint8_t> in, BusReply* reply, std::size_t* used, std::size_t* want) noexcept override;
  std::size_t encode_retry(std::uint32_t device, std::span<std::uint8_t> out) noexcept override;

 private:
  std::array<std::uint8_t, kMaxPacket> scratch_{};
};

}  // namespace avar::firmware_iface
