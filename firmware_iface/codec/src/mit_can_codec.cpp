#include "avar/firmware_iface/mit_can_codec.hpp"

#include <algorithm>
#include <cmath>

#include "avar/core/byte_order.hpp"

namespace avar::firmware_iface::mit {
namespace {

constexpr std::uint8_t kSpecialLastByte[] = {0, 0xFC, 0xFD, 0xFE};  // by MitFrameKind
constexpr std::uint16_t kTorqueBelowSpecial = 0xFFB;

bool ordered(double lo, double hi) noexcept { return std::isfinite(lo) && std::isfinite(hi) && lo < hi; }

std::uint16_t field(double x, double min, double max, int bits) noexcept {
  return static_cast<std::uint16_t>(float_to_uint(x, min, max, bits));
}

}  // namespace

bool MitRanges::valid() const noexcept {
  return ordered(p_min, p_max) && ordered(v_min, v_max) && ordered(0, kp_max) && ordered(0, kd_max) && ordered(t_min, t_max);
}

const MitRanges* find_ranges(std::string_view model) noexcept {
  for (const NamedMitRanges& n : kNamedRanges)
    if (n.name == model) return &n.ranges;
  return nullptr;
}

std::uint32_t float_to_uint(double x, double min, double max, int bits) noexcept {
  // Single precision throughout, in the firmware's order of operations.
  const float lo = static_cast<float>(min);
  const float hi = static_cast<float>(max);
  const float span = hi - lo;
  const float top = static_cast<float>((1u << bits) - 1u);
  float xf = std::isnan(x) ? 0.5f * (lo + hi) : static_cast<float>(std::clamp(x, min, max));
  xf = std::clamp(xf, lo, hi);
  const float scaled = (xf - lo) * top / span;
  return static_cast<std::uint32_t>(std::clamp(scaled, 0.0f, top));  // truncates toward zero
}

double uint_to_float(std::uint32_t u, double min, double max, int bits) noexcept {
  const float lo = static_cast<float>(min);
  const float span = static_cast<float>(max) - lo;
  const float top = static_cast<float>((1u << bits) - 1u);
  return static_cast<double>(static_cast<float>(u) * span / top + lo);
}

MitCommandBits quantise_command(const MitCommand& c, const MitRanges& r) noexcept {
  MitCommandBits b;
  b.p = field(c.position, r.p_min, r.p_max, kPositionBits);
  b.v = field(c.velocity, r.v_min, r.v_max, kVelocityBits);
  b.kp = field(c.kp, 0, r.kp_max, kGainBits);
  b.kd = field(c.kd, 0, r.kd_max, kGainBits);
  b.t = field(c.torque, r.t_min, r.t_max, kTorqueBits);
  const bool rest_full = b.p == 0xFFFF && b.v == 0xFFF && b.kp == 0xFFF && b.kd == 0xFFF;
  if (rest_full && b.t >= 0xFFC && b.t <= 0xFFE) b.t = kTorqueBelowSpecial;
  return b;
}

std::array<std::uint8_t, 8> pack_command(const MitCommandBits& b) noexcept {
  const unsigned v = b.v & 0xFFFu, kp = b.kp & 0xFFFu, kd = b.kd & 0xFFFu, t = b.t & 0xFFFu;
  std::array<std::uint8_t, 8> d{};
  put_u16_be(&d[0], b.p);
  // Then three pairs of 12-bit fields, each pair in three bytes, most significant first.
  put_be(&d[2], v << 12 | kp, 3);
  put_be(&d[5], kd << 12 | t, 3);
  return d;
}

MitCommandBits unpack_command(std::span<const std::uint8_t, 8> d) noexcept {
  MitCommandBits b;
  b.p = get_u16_be(&d[0]);
  const std::uint32_t v_kp = get_be(&d[2], 3), kd_t = get_be(&d[5], 3);
  b.v = static_cast<std::uint16_t>(v_kp >> 12);
  b.kp = static_cast<std::uint16_t>(v_kp & 0xFFF);
  b.kd = static_cast<std::uint16_t>(kd_t >> 12);
  b.t = static_cast<std::uint16_t>(kd_t & 0xFFF);
  return b;
}

MitCommand command_value(const MitCommandBits& b, const MitRanges& r) noexcept {
  return {uint_to_float(b.p, r.p_min, r.p_max, kPositionBits), uint_to_float(b.v, r.v_min, r.v_max, kVelocityBits),
          uint_to_float(b.kp, 0, r.kp_max, kGainBits), uint_to_float(b.kd, 0, r.kd_max, kGainBits),
          uint_to_float(b.t, r.t_min, r.t_max, kTorqueBits)};
}

CanFrame command_frame(std::uint32_t node, const MitCommand& command, const MitRanges& ranges) noexcept {
  const std::array<std::uint8_t, 8> data = pack_command(quantise_command(command, ranges));
  return can_data_frame(node, data);
}

MitFrameKind classify(std::span<const std::uint8_t, 8> d) noexcept {
  if (!std::all_of(d.begin(), d.begin() + 7, [](std::uint8_t b) { return b == 0xFF; })) return MitFrameKind::command;
  switch (d[7]) {
    case 0xFC: return MitFrameKind::enter_motor_mode;
    case 0xFD: return MitFrameKind::exit_motor_mode;
    case 0xFE: return MitFrameKind::set_zero;
    default: return MitFrameKind::command;
  }
}

std::array<std::uint8_t, 8> special_data(MitFrameKind kind) noexcept {
  if (kind == MitFrameKind::command) return {};
  return {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, kSpecialLastByte[static_cast<int>(kind)]};
}

CanFrame special_frame(std::uint32_t node, MitFrameKind kind) noexcept {
  const std::array<std::uint8_t, 8> data = special_data(kind);
  return can_data_frame(node, data);
}

std::array<std::uint8_t, 6> pack_reply(std::uint8_t id, double position, double velocity, double torque,
                                       const MitRanges& r) noexcept {
  const unsigned p = float_to_uint(position, r.p_min, r.p_max, kPositionBits);
  const unsigned v = float_to_uint(velocity, r.v_min, r.v_max, kVelocityBits);
  const unsigned t = float_to_uint(torque, r.t_min, r.t_max, kTorqueBits);
  std::array<std::uint8_t, 6> d{id};
  put_u16_be(&d[1], static_cast<std::uint16_t>(p));
  put_be(&d[3], (v & 0xFFFu) << 12 | (t & 0xFFFu), 3);  // two 12-bit fields in three bytes
  return d;
}

bool unpack_reply(std::span<const std::uint8_t> d, MitReplyBits* out) noexcept {
  if (d.size() < 6) return false;
  out->id = d[0];
  out->p = get_u16_be(&d[1]);
  const std::uint32_t v_t = get_be(&d[3], 3);
  out->v = static_cast<std::uint16_t>(v_t >> 12);
  out->t = static_cast<std::uint16_t>(v_t & 0xFFF);
  return true;
}

bool decode_reply(std::span<const std::uint8_t> d, const MitRanges& r, const MitReplyFormat& format, MitReply* out) noexcept {
  if (d.size() < 6 || (d.size() > 6 && !format.accept_longer)) return false;
  MitReplyBits b;
  unpack_reply(d, &b);
  out->id = static_cast<std::uint8_t>(b.id & format.id_mask);
  out->position = uint_to_float(b.p, r.p_min, r.p_max, kPositionBits);
  out->velocity = uint_to_float(b.v, r.v_min, r.v_max, kVelocityBits);
  out->torque = uint_to_float(b.t, r.t_min, r.t_max, kTorqueBits);
  return true;
}

}  // namespace avar::firmware_iface::mit
