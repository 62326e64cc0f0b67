#pragma once
// A CAN frame from fuzz bytes: 4 bytes of id (bit 31: extended, bit 30: remote), a DLC byte
// (taken modulo 9, as every transport delivers 0..8) and up to 8 data bytes.

#include <algorithm>

#include "avar/firmware_iface/can_frame.hpp"
#include "fuzz_bytes.hpp"

namespace avar::fuzz {

inline firmware_iface::CanFrame read_can_frame(ByteReader& in) {
  firmware_iface::CanFrame frame;
  const std::uint32_t word = in.u32();
  frame.extended = (word & 0x8000'0000u) != 0;
  frame.rtr = (word & 0x4000'0000u) != 0;
  frame.id = word & (frame.extended ? 0x1FFF'FFFFu : 0x7FFu);
  frame.dlc = static_cast<std::uint8_t>(in.u8() % 9);
  const auto data = in.take(frame.dlc);
  std::copy(data.begin(), data.end(), frame.data.begin());
  return frame;
}

}  // namespace avar::fuzz
