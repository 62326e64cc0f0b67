#pragma once
// Byte order on the wire: unsigned, signed (two's complement) and IEEE 754 binary32 values written
// to and read from bytes, least significant byte first (_le: DYNAMIXEL, Feetech STS, Maestro,
// ODrive, CANopen, USB, DMX widgets, Art-Net's little-endian fields) or most significant first
// (_be: Art-Net, sACN, OSC, MIT motors, Feetech SCS), whatever the host's own order.
//
// `p` points at the value's first byte; the caller has checked that the bytes are there.
// Everything is constexpr, allocation-free and needs no system library: pure codecs use it, on
// the host and on a microcontroller alike.

#include <bit>
#include <cstddef>
#include <cstdint>

namespace avar {

// ---- least significant byte first ------------------------------------------------------------

/// Writes the low `size` bytes (0..4) of `v` to p[0..size), least significant first.
constexpr void put_le(std::uint8_t* p, std::uint32_t v, std::size_t size) noexcept {
  for (std::size_t i = 0; i < size; ++i) p[i] = static_cast<std::uint8_t>(v >> (8 * i));
}
/// Reads `size` bytes (0..4) from p[0..size), least significant first, into the low bytes.
constexpr std::uint32_t get_le(const std::uint8_t* p, std::size_t size) noexcept {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < size; ++i) v |= static_cast<std::uint32_t>(p[i]) << (8 * i);
  return v;
}

constexpr void put_u16_le(std::uint8_t* p, std::uint16_t v) noexcept { put_le(p, v, 2); }
constexpr void put_u32_le(std::uint8_t* p, std::uint32_t v) noexcept { put_le(p, v, 4); }
constexpr void put_i16_le(std::uint8_t* p, std::int16_t v) noexcept { put_le(p, static_cast<std::uint16_t>(v), 2); }
constexpr void put_i32_le(std::uint8_t* p, std::int32_t v) noexcept { put_le(p, static_cast<std::uint32_t>(v), 4); }
constexpr void put_f32_le(std::uint8_t* p, float v) noexcept { put_le(p, std::bit_cast<std::uint32_t>(v), 4); }

constexpr std::uint16_t get_u16_le(const std::uint8_t* p) noexcept { return static_cast<std::uint16_t>(get_le(p, 2)); }
constexpr std::uint32_t get_u32_le(const std::uint8_t* p) noexcept { return get_le(p, 4); }
constexpr std::int16_t get_i16_le(const std::uint8_t* p) noexcept { return static_cast<std::int16_t>(get_le(p, 2)); }
constexpr std::int32_t get_i32_le(const std::uint8_t* p) noexcept { return static_cast<std::int32_t>(get_le(p, 4)); }
constexpr float get_f32_le(const std::uint8_t* p) noexcept { return std::bit_cast<float>(get_le(p, 4)); }

// ---- most significant byte first -------------------------------------------------------------

/// Writes the low `size` bytes (0..4) of `v` to p[0..size), most significant first.
constexpr void put_be(std::uint8_t* p, std::uint32_t v, std::size_t size) noexcept {
  for (std::size_t i = 0; i < size; ++i) p[i] = static_cast<std::uint8_t>(v >> (8 * (size - 1 - i)));
}
/// Reads `size` bytes (0..4) from p[0..size), most significant first, into the low bytes.
constexpr std::uint32_t get_be(const std::uint8_t* p, std::size_t size) noexcept {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < size; ++i) v = v << 8 | p[i];
  return v;
}

constexpr void put_u16_be(std::uint8_t* p, std::uint16_t v) noexcept { put_be(p, v, 2); }
constexpr void put_u32_be(std::uint8_t* p, std::uint32_t v) noexcept { put_be(p, v, 4); }
constexpr void put_i16_be(std::uint8_t* p, std::int16_t v) noexcept { put_be(p, static_cast<std::uint16_t>(v), 2); }
constexpr void put_i32_be(std::uint8_t* p, std::int32_t v) noexcept { put_be(p, static_cast<std::uint32_t>(v), 4); }
constexpr void put_f32_be(std::uint8_t* p, float v) noexcept { put_be(p, std::bit_cast<std::uint32_t>(v), 4); }

constexpr std::uint16_t get_u16_be(const std::uint8_t* p) noexcept { return static_cast<std::uint16_t>(get_be(p, 2)); }
constexpr std::uint32_t get_u32_be(const std::uint8_t* p) noexcept { return get_be(p, 4); }
constexpr std::int16_t get_i16_be(const std::uint8_t* p) noexcept { return static_cast<std::int16_t>(get_be(p, 2)); }
constexpr std::int32_t get_i32_be(const std::uint8_t* p) noexcept { return static_cast<std::int32_t>(get_be(p, 4)); }
constexpr float get_f32_be(const std::uint8_t* p) noexcept { return std::bit_cast<float>(get_be(p, 4)); }

}  // namespace avar
