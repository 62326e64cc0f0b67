#pragma once
// Pololu Maestro over native USB: the vendor control requests of the Maestro's own USB interface
// (beside its two virtual serial ports), as setup packets, and the decoders of their replies.
// Pure: no I/O, no clock, no allocation, no exception; every function is real-time safe and may
// be called from any thread.
//
// Source: Pololu's USB SDK (github.com/pololu/pololu-usb-sdk), Maestro/Usc/Usc_protocol.cs (the
// uscRequest values, the ServoStatus, MicroMaestroVariables and MiniMaestroVariables layouts,
// all packed, little-endian) and Maestro/Usc/Usc.cs (vendor and product ids, which request
// carries what in wValue and wIndex, and the reply lengths). Summary:
//   out (bmRequestType 0x40, no data stage)
//     Set Target          bRequest 0x85  wValue = target (quarter-µs)  wIndex = channel
//     Set Speed           bRequest 0x84  wValue = speed                 wIndex = channel
//     Set Acceleration    bRequest 0x84  wValue = acceleration          wIndex = channel | 0x80
//     Clear Errors        bRequest 0x86  wValue = 0                     wIndex = 0
//   in (bmRequestType 0xC0)
//     Get Variables       bRequest 0x83  wValue = 0 wIndex = 0
//       Micro Maestro 6:  wLength 140 = 98 bytes of variables (errors at offset 2), then
//                         6 servo records from offset 98
//       Mini Maestro:     wLength 8 (errors at offset 2); no servo records
//     Get Servo Settings  bRequest 0x87  wValue = 0 wIndex = 0, Mini Maestro only:
//                         wLength = 7 × channels, the servo records
//   A servo record (7 bytes): position u16 (quarter-µs, the pulse output now), target u16,
//   speed u16, acceleration u8.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "avar/firmware_iface/usb_setup.hpp"

namespace avar::firmware_iface::maestro_usb {

using SetupPacket = UsbSetup;

inline constexpr std::uint16_t kVendorId = 0x1FFB;  ///< Pololu
/// Product ids: Micro Maestro 6, Mini Maestro 12, 18, 24.
inline constexpr std::array<std::uint16_t, 4> kProductIds{0x0089, 0x008A, 0x008B, 0x008C};
/// The product id of the Maestro with this many channels (6, 12, 18, 24), or 0.
std::uint16_t product_id_for_channels(int channel_count) noexcept;
/// The channel count of a Maestro product id, or 0 for another product.
int channels_for_product_id(std::uint16_t product_id) noexcept;

inline constexpr std::uint8_t kVendorOut = 0x40;
inline constexpr std::uint8_t kVendorIn = 0xC0;

enum Request : std::uint8_t {
  kGetVariables = 0x83,
  kSetServoVariable = 0x84,
  kSetTarget = 0x85,
  kClearErrors = 0x86,
  kGetServoSettings = 0x87,  ///< Mini Maestro only
};

/// wIndex bit of Set Servo Variable that selects the acceleration instead of the speed.
inline constexpr std::uint16_t kAccelerationFlag = 0x80;
/// Bytes of one servo record.
inline constexpr std::size_t kServoRecordSize = 7;
/// Micro Maestro: variables before the servo records (stack and call stack included).
inline constexpr std::size_t kMicroVariablesSize = 98;
/// Mini Maestro: the variables Get Variables answers.
inline constexpr std::size_t kMiniVariablesSize = 8;
/// Offset of the error register (u16) in both variable layouts.
inline constexpr std::size_t kErrorsOffset = 2;
/// The longest reply: Get Servo Settings of a Mini Maestro 24.
inline constexpr std::size_t kMaxReplySize = 24 * kServoRecordSize;

/// Set Target: channel 0..23, target in quarter-µs (0 = no pulses).
SetupPacket set_target(std::uint8_t channel, std::uint16_t quarter_us) noexcept;
/// Set Speed: units of 25 µs/s at the 20 ms period (0 = unlimited), as the serial command.
SetupPacket set_speed(std::uint8_t channel, std::uint16_t speed) noexcept;
/// Set Acceleration: units of 312.5 µs/s² (0 = unlimited); saturates at 255.
SetupPacket set_acceleration(std::uint8_t channel, std::uint16_t acceleration) noexcept;
/// Clear Errors: the error register becomes 0.
SetupPacket clear_errors() noexcept;
/// Get Variables, sized for the model (channel_count 6: the Micro layout with its servo
/// records; 12, 18, 24: the Mini layout).
SetupPacket get_variables(int channel_count) noexcept;
/// Get Servo Settings of a Mini Maestro with channel_count channels (the servo records).
SetupPacket get_servo_settings(int channel_count) noexcept;
/// The request that returns the servo records of this model: Get Variables on the Micro
/// Maestro, Get Servo Settings on a Mini Maestro.
SetupPacket get_positions(int channel_count) noexcept;

/// One channel's record.
struct ServoStatus {
  std::uint16_t position = 0;  ///< quarter-µs: the pulse output now (0 = none)
  std::uint16_t target = 0;    ///< quarter-µs
  std::uint16_t speed = 0;
  std::uint8_t acceleration = 0;
  bool operator==(const ServoStatus&) const = default;
};

/// Writes one record in the device's layout (for simulated devices). out.size() >= 7.
void encode_servo_status(std::span<std::uint8_t> out, const ServoStatus& status) noexcept;
/// Reads record `channel` from the reply of get_positions(channel_count). Returns false
/// (leaving *out alone) when the reply is too short to hold it.
bool decode_servo_status(std::span<const std::uint8_t> reply, int channel_count, int channel, ServoStatus* out) noexcept;
/// The error register from a Get Variables reply (either layout). Returns false when the reply
/// is shorter than kMiniVariablesSize.
bool decode_errors(std::span<const std::uint8_t> reply, std::uint16_t* errors) noexcept;

}  // namespace avar::firmware_iface::maestro_usb
