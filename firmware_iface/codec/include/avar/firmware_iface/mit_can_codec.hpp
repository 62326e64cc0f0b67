#pragma once
// MIT mini-cheetah style CAN motors, "MIT mode" (../shared/protocols/mit-cheetah-can.md): pure
// encoders and decoders of the command, special and reply frames. The value ranges differ per
// motor model, so every conversion takes them as a MitRanges. No I/O, no clock, no allocation,
// no exception: every function is real-time safe.
//
// Units: position rad, velocity rad/s, kp N·m/rad, kd N·m·s/rad, torque N·m (at the output shaft).

#include <array>
#include <cstdint>
#include <span>
#include <string_view>

#include "avar/firmware_iface/can_frame.hpp"

namespace avar::firmware_iface::mit {

/// The range every field of a command or reply is scaled over (a motor model's flash settings).
struct MitRanges {
  double p_min = -12.5;  ///< rad
  double p_max = 12.5;   ///< rad
  double v_min = -65;    ///< rad/s
  double v_max = 65;     ///< rad/s
  double kp_max = 500;   ///< N·m/rad (kp_min is 0)
  double kd_max = 5;     ///< N·m·s/rad (kd_min is 0)
  double t_min = -18;    ///< N·m
  double t_max = 18;     ///< N·m

  /// Every bound finite, each min below its max, kp_max and kd_max above 0.
  bool valid() const noexcept;
};

/// Ranges named by what the notes (§5) say they are.
/// The notes' test ranges: the bgkatz firmware's defaults (P ±12.5, V ±65, KP 500, KD 5) with the
/// original Mini Cheetah's ±18 N·m.
inline constexpr MitRanges kMiniCheetahRanges{-12.5, 12.5, -65, 65, 500, 5, -18, 18};
/// The ranges written in the bgkatz firmware's comments: ±4π rad, ±30 rad/s, KP 500, KD 100, ±18 N·m.
inline constexpr MitRanges kBgkatzCommentRanges{-12.566370614359172, 12.566370614359172, -30, 30, 500, 100, -18, 18};
/// The HT04 header the notes cite: ±95.5 rad, ±45 rad/s, ±35 N·m. The notes give no gains for it;
/// these use the common KP 500, KD 5.
inline constexpr MitRanges kHt04HeaderRanges{-95.5, 95.5, -45, 45, 500, 5, -35, 35};

/// The presets by the names rig files use (`model: mini-cheetah`).
struct NamedMitRanges {
  std::string_view name;
  MitRanges ranges;
};
inline constexpr std::array<NamedMitRanges, 3> kNamedRanges{{
    {"mini-cheetah", kMiniCheetahRanges},
    {"bgkatz-comments", kBgkatzCommentRanges},
    {"ht04", kHt04HeaderRanges},
}};
/// The preset called `model`, or null.
const MitRanges* find_ranges(std::string_view model) noexcept;

inline constexpr int kPositionBits = 16;
inline constexpr int kVelocityBits = 12;
inline constexpr int kGainBits = 12;
inline constexpr int kTorqueBits = 12;

/// The firmware's float_to_uint (math_ops.c), in single precision as the firmware computes it:
/// (int)((x - min) * ((1 << bits) - 1) / (max - min)), truncating toward zero. The host clamps
/// first: x to [min, max] (NaN becomes the centre of the range) and the result to the bit field,
/// so a value never wraps. Precondition: min < max, 1 <= bits <= 16.
std::uint32_t float_to_uint(double x, double min, double max, int bits) noexcept;
/// The firmware's uint_to_float, in single precision: u * (max - min) / ((1 << bits) - 1) + min.
double uint_to_float(std::uint32_t u, double min, double max, int bits) noexcept;

/// One command as the host means it (clamped to the ranges when packed).
struct MitCommand {
  double position = 0;  ///< rad
  double velocity = 0;  ///< rad/s
  double kp = 0;        ///< N·m/rad
  double kd = 0;        ///< N·m·s/rad
  double torque = 0;    ///< feed-forward, N·m
};

/// A command's fields as the integers on the wire.
struct MitCommandBits {
  std::uint16_t p = 0;   ///< 16 bits
  std::uint16_t v = 0;   ///< 12 bits
  std::uint16_t kp = 0;  ///< 12 bits
  std::uint16_t kd = 0;  ///< 12 bits
  std::uint16_t t = 0;   ///< 12 bits
  bool operator==(const MitCommandBits&) const noexcept = default;
};

/// Quantises a command (each field clamped to its range first). When every other field is full
/// scale, a torque that would pack to FC/FD/FE in the last byte (a special frame, §6 hazard) is
/// lowered to the value just below (0xFFB), so no command is ever read as enter, exit or zero.
/// (Merely clamping the torque slightly below t_max would not do: truncation puts it at 0xFFE,
/// "set zero".)
MitCommandBits quantise_command(const MitCommand& command, const MitRanges& ranges) noexcept;
/// Packs the integers (16/12/12/12/12 bits, big-endian, §3). Fields wider than their bits are cut.
std::array<std::uint8_t, 8> pack_command(const MitCommandBits& bits) noexcept;
/// Splits a command payload into its integers (the firmware's unpack_cmd).
MitCommandBits unpack_command(std::span<const std::uint8_t, 8> data) noexcept;
/// The command the firmware decodes from the integers (uint_to_float of each field).
MitCommand command_value(const MitCommandBits& bits, const MitRanges& ranges) noexcept;

/// quantise_command then pack_command, as a data frame to the motor's CAN_ID (11-bit).
CanFrame command_frame(std::uint32_t node, const MitCommand& command, const MitRanges& ranges) noexcept;

/// What an 8-byte frame to a motor asks for.
enum class MitFrameKind : std::uint8_t {
  command,           ///< any other 8-byte payload
  enter_motor_mode,  ///< FF ×7 FC
  exit_motor_mode,   ///< FF ×7 FD
  set_zero,          ///< FF ×7 FE: the present position becomes zero
};
/// Classifies an 8-byte payload as the firmware does.
MitFrameKind classify(std::span<const std::uint8_t, 8> data) noexcept;
/// The payload of a special frame (kind must not be command; command yields all zero bytes).
std::array<std::uint8_t, 8> special_data(MitFrameKind kind) noexcept;
/// A special frame to the motor's CAN_ID.
CanFrame special_frame(std::uint32_t node, MitFrameKind kind) noexcept;

/// A reply (motor -> host) as the integers on the wire.
struct MitReplyBits {
  std::uint8_t id = 0;  ///< byte 0: the motor's CAN_ID (low 8 bits)
  std::uint16_t p = 0;  ///< 16 bits
  std::uint16_t v = 0;  ///< 12 bits
  std::uint16_t t = 0;  ///< 12 bits
  bool operator==(const MitReplyBits&) const noexcept = default;
};
/// A reply in physical units.
struct MitReply {
  std::uint8_t id = 0;  ///< byte 0 with MitReplyFormat::id_mask applied
  double position = 0;  ///< rad
  double velocity = 0;  ///< rad/s
  double torque = 0;    ///< measured, N·m
};

/// How a motor model's replies are laid out beyond the 6 bytes of §4 (clones vary: unconfirmed).
struct MitReplyFormat {
  /// Accept replies longer than 6 bytes whose first 6 follow §4 (clones that append temperature
  /// and an error code); the extra bytes are ignored. false: exactly 6 bytes.
  bool accept_longer = true;
  /// The bits of byte 0 that hold the motor ID (0x0F for clones with error bits in the high nibble).
  std::uint8_t id_mask = 0xFF;
};

/// Quantises a reply (fields clamped to their ranges) and packs it into 6 bytes (§4).
std::array<std::uint8_t, 6> pack_reply(std::uint8_t id, double position, double velocity, double torque,
                                       const MitRanges& ranges) noexcept;
/// Splits the first 6 bytes of a reply into its integers; false when fewer than 6.
bool unpack_reply(std::span<const std::uint8_t> data, MitReplyBits* out) noexcept;
/// Decodes a reply payload: false when its length does not fit `format`.
bool decode_reply(std::span<const std::uint8_t> data, const MitRanges& ranges, const MitReplyFormat& format,
                  MitReply* out) noexcept;

}  // namespace avar::firmware_iface::mit
