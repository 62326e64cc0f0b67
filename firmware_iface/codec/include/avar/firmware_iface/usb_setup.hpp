#pragma once
// A USB setup packet: the 8 bytes that open a control transfer (USB 2.0 §9.3). Plain data;
// real-time safe.

#include <array>
#include <cstdint>

#include "avar/core/byte_order.hpp"

namespace avar::firmware_iface {

struct UsbSetup {
  std::uint8_t request_type = 0;  ///< bmRequestType (vendor requests: 0x40 out, 0xC0 in)
  std::uint8_t request = 0;       ///< bRequest
  std::uint16_t value = 0;        ///< wValue
  std::uint16_t index = 0;        ///< wIndex
  std::uint16_t length = 0;       ///< wLength: bytes of the data stage
  bool operator==(const UsbSetup&) const = default;
  /// Whether the data stage goes from the device to the host (bit 7 of bmRequestType).
  bool device_to_host() const noexcept { return (request_type & 0x80) != 0; }
  /// The packet as it goes on the wire (words little-endian).
  std::array<std::uint8_t, 8> bytes() const noexcept {
    std::array<std::uint8_t, 8> b{request_type, request};
    put_u16_le(&b[2], value);
    put_u16_le(&b[4], index);
    put_u16_le(&b[6], length);
    return b;
  }
};

}  // namespace avar::firmware_iface
