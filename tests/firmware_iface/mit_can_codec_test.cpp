// Golden frames from ../shared/protocols/mit-cheetah-can.md, section 6 (vectors K1..K6), the
// firmware's float <-> uint mapping, and seeded round trips over every field.
#include "avar/firmware_iface/mit_can_codec.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace avar::firmware_iface::mit {
namespace {

using MitBytes = std::vector<std::uint8_t>;

MitBytes mit_bytes(std::span<const std::uint8_t> data) { return MitBytes(data.begin(), data.end()); }

MitBytes mit_command_bytes(double p, double v, double kp, double kd, double t) {
  return mit_bytes(pack_command(quantise_command({p, v, kp, kd, t}, kMiniCheetahRanges)));
}

TEST(MitCodec, RangesPresetsAreValidAndBadRangesAreNot) {
  EXPECT_TRUE(kMiniCheetahRanges.valid());
  EXPECT_TRUE(kBgkatzCommentRanges.valid());
  EXPECT_TRUE(kHt04HeaderRanges.valid());
  EXPECT_EQ(kMiniCheetahRanges.p_max, 12.5);
  EXPECT_EQ(kMiniCheetahRanges.v_max, 65);
  EXPECT_EQ(kMiniCheetahRanges.kp_max, 500);
  EXPECT_EQ(kMiniCheetahRanges.kd_max, 5);
  EXPECT_EQ(kMiniCheetahRanges.t_min, -18);
  MitRanges r;
  r.p_min = r.p_max;
  EXPECT_FALSE(r.valid());
  r = {};
  r.kd_max = 0;
  EXPECT_FALSE(r.valid());
  r = {};
  r.t_max = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(r.valid());
  r = {};
  r.v_min = std::nan("");
  EXPECT_FALSE(r.valid());
}

TEST(MitCodec, PresetsAreFoundByTheirModelNames) {
  ASSERT_NE(find_ranges("mini-cheetah"), nullptr);
  EXPECT_EQ(find_ranges("mini-cheetah")->t_max, 18);
  ASSERT_NE(find_ranges("ht04"), nullptr);
  EXPECT_EQ(find_ranges("ht04")->p_max, 95.5);
  ASSERT_NE(find_ranges("bgkatz-comments"), nullptr);
  EXPECT_EQ(find_ranges("bgkatz-comments")->kd_max, 100);
  EXPECT_EQ(find_ranges("ak80"), nullptr);
}

TEST(MitCodec, K1_ZeroCommand) {
  const MitCommandBits b = quantise_command({}, kMiniCheetahRanges);
  EXPECT_EQ(b, (MitCommandBits{32767, 2047, 0, 0, 2047}));
  EXPECT_EQ(mit_command_bytes(0, 0, 0, 0, 0), (MitBytes{0x7F, 0xFF, 0x7F, 0xF0, 0x00, 0x00, 0x07, 0xFF}));
}

TEST(MitCodec, K2_HoldOneRadian) {
  EXPECT_EQ(quantise_command({1.0, 0, 20.0, 0.5, 0}, kMiniCheetahRanges), (MitCommandBits{35388, 2047, 163, 409, 2047}));
  EXPECT_EQ(mit_command_bytes(1.0, 0, 20.0, 0.5, 0), (MitBytes{0x8A, 0x3C, 0x7F, 0xF0, 0xA3, 0x19, 0x97, 0xFF}));
}

TEST(MitCodec, K3_K4_BottomAndFullScale) {
  EXPECT_EQ(mit_command_bytes(-12.5, -65, 0, 0, -18), MitBytes(8, 0x00));
  EXPECT_EQ(quantise_command({12.5, 65, 500, 5, 18}, kMiniCheetahRanges), (MitCommandBits{65535, 4095, 4095, 4095, 4095}));
  const MitBytes full = mit_command_bytes(12.5, 65, 500, 5, 18);
  EXPECT_EQ(full, MitBytes(8, 0xFF));
  EXPECT_EQ(classify(std::span<const std::uint8_t, 8>(full.data(), 8)), MitFrameKind::command);
}

TEST(MitCodec, K5_ReplyAtZero) {
  const MitBytes golden{0x01, 0x7F, 0xFF, 0x7F, 0xF7, 0xFF};
  EXPECT_EQ(mit_bytes(pack_reply(1, 0, 0, 0, kMiniCheetahRanges)), golden);
  MitReplyBits bits;
  ASSERT_TRUE(unpack_reply(golden, &bits));
  EXPECT_EQ(bits, (MitReplyBits{1, 32767, 2047, 2047}));
  MitReply r;
  ASSERT_TRUE(decode_reply(golden, kMiniCheetahRanges, {}, &r));
  EXPECT_EQ(r.id, 1);
  // Truncation: zero decodes slightly below zero (notes §3).
  EXPECT_NEAR(r.position, -0.00019, 1e-5);
  EXPECT_NEAR(r.velocity, -0.0159, 1e-4);
  EXPECT_LT(r.torque, 0);
  EXPECT_GT(r.torque, -0.005);
}

TEST(MitCodec, K6_SpecialFramesAndTheirClassification) {
  EXPECT_EQ(mit_bytes(special_data(MitFrameKind::enter_motor_mode)), (MitBytes{0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFC}));
  EXPECT_EQ(mit_bytes(special_data(MitFrameKind::exit_motor_mode)), (MitBytes{0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFD}));
  EXPECT_EQ(mit_bytes(special_data(MitFrameKind::set_zero)), (MitBytes{0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFE}));
  for (MitFrameKind k : {MitFrameKind::enter_motor_mode, MitFrameKind::exit_motor_mode, MitFrameKind::set_zero})
    EXPECT_EQ(classify(special_data(k)), k);
  const std::array<std::uint8_t, 8> almost{0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFE, 0xFC};
  EXPECT_EQ(classify(almost), MitFrameKind::command);
  const CanFrame f = special_frame(0x7FF, MitFrameKind::enter_motor_mode);
  EXPECT_EQ(f.id, 0x7FFu);
  EXPECT_FALSE(f.extended);
  EXPECT_EQ(f.dlc, 8);
  EXPECT_EQ(mit_bytes(f.payload()), mit_bytes(special_data(MitFrameKind::enter_motor_mode)));
}

TEST(MitCodec, CommandFrameGoesToTheMotorsCanId) {
  const CanFrame f = command_frame(3, {1.0, 0, 20.0, 0.5, 0}, kMiniCheetahRanges);
  EXPECT_EQ(f.id, 3u);
  EXPECT_FALSE(f.extended);
  EXPECT_FALSE(f.rtr);
  EXPECT_EQ(mit_bytes(f.payload()), (MitBytes{0x8A, 0x3C, 0x7F, 0xF0, 0xA3, 0x19, 0x97, 0xFF}));
}

TEST(MitCodec, FloatToUintTruncatesTowardZeroLikeTheFirmware) {
  EXPECT_EQ(float_to_uint(0, -12.5, 12.5, 16), 32767u);  // 32767.5
  EXPECT_EQ(float_to_uint(0.5, 0, 5, 12), 409u);         // 409.5
  EXPECT_EQ(float_to_uint(20, 0, 500, 12), 163u);        // 163.8
  EXPECT_EQ(float_to_uint(-12.5, -12.5, 12.5, 16), 0u);
  EXPECT_EQ(float_to_uint(12.5, -12.5, 12.5, 16), 65535u);
  EXPECT_FLOAT_EQ(static_cast<float>(uint_to_float(0, -65, 65, 12)), -65.0f);
  EXPECT_FLOAT_EQ(static_cast<float>(uint_to_float(4095, -65, 65, 12)), 65.0f);
  EXPECT_FLOAT_EQ(static_cast<float>(uint_to_float(163, 0, 500, 12)), 163.0f * 500.0f / 4095.0f);
}

TEST(MitCodec, OutOfRangeValuesSaturateAndNeverWrapTheField) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(float_to_uint(13.0, -12.5, 12.5, 16), 65535u);
  EXPECT_EQ(float_to_uint(1e9, -12.5, 12.5, 16), 65535u);
  EXPECT_EQ(float_to_uint(inf, -12.5, 12.5, 16), 65535u);
  EXPECT_EQ(float_to_uint(-13.0, -12.5, 12.5, 16), 0u);
  EXPECT_EQ(float_to_uint(-inf, -12.5, 12.5, 16), 0u);
  EXPECT_EQ(float_to_uint(std::nan(""), -12.5, 12.5, 16), 32767u);  // centre
  EXPECT_EQ(float_to_uint(-1, 0, 500, 12), 0u);                     // gains never negative
  EXPECT_EQ(quantise_command({100, -100, 1e4, -3, 99}, kMiniCheetahRanges), (MitCommandBits{65535, 0, 4095, 0, 4095}));
}

TEST(MitCodec, NoCommandEverPacksToASpecialFrame) {
  // Full scale everywhere but the torque: torques that would pack to FC, FD or FE are lowered to FB.
  const MitRanges r = kMiniCheetahRanges;
  const double quantum = (r.t_max - r.t_min) / 4095;
  for (double t :
       {r.t_max - 0.5 * quantum, r.t_max - 1.5 * quantum, r.t_max - 2.5 * quantum, r.t_max - 3.5 * quantum, r.t_max - 1e-4}) {
    const MitCommandBits b = quantise_command({r.p_max, r.v_max, r.kp_max, r.kd_max, t}, r);
    SCOPED_TRACE(t);
    EXPECT_LE(b.t, 0xFFBu);
    EXPECT_GE(b.t, 0xFF8u);
    EXPECT_EQ(classify(pack_command(b)), MitFrameKind::command);
  }
  // Anything short of full scale elsewhere keeps its torque.
  EXPECT_EQ(quantise_command({r.p_max, r.v_max, r.kp_max, 4.99, r.t_max - 1e-4}, r).t, 0xFFEu);
}

TEST(MitCodec, ReplyDecoderToleratesLongerCloneRepliesWhenAsked) {
  const MitBytes eight{0x01, 0x7F, 0xFF, 0x7F, 0xF7, 0xFF, 0x28, 0x00};  // + temperature, error code
  MitReply r;
  ASSERT_TRUE(decode_reply(eight, kMiniCheetahRanges, {}, &r));
  EXPECT_EQ(r.id, 1);
  EXPECT_NEAR(r.position, 0, 1e-3);
  EXPECT_FALSE(decode_reply(eight, kMiniCheetahRanges, {.accept_longer = false}, &r));
  EXPECT_FALSE(decode_reply(std::span(eight).first(5), kMiniCheetahRanges, {}, &r));
  const MitBytes nibble{0x93, 0x7F, 0xFF, 0x7F, 0xF7, 0xFF};  // error bits 0x9 in byte 0's high nibble, ID 3
  ASSERT_TRUE(decode_reply(nibble, kMiniCheetahRanges, {.accept_longer = true, .id_mask = 0x0F}, &r));
  EXPECT_EQ(r.id, 3);
}

TEST(MitCodec, SeededCommandRoundTripsStayWithinOneQuantum) {
  const unsigned seed = 20240611;
  SCOPED_TRACE(seed);
  std::mt19937 rng(seed);
  for (const MitRanges& r : {kMiniCheetahRanges, kBgkatzCommentRanges, kHt04HeaderRanges}) {
    auto in = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
    const double qp = (r.p_max - r.p_min) / 65535, qv = (r.v_max - r.v_min) / 4095;
    const double qkp = r.kp_max / 4095, qkd = r.kd_max / 4095, qt = (r.t_max - r.t_min) / 4095;
    for (int i = 0; i < 2000; ++i) {
      const MitCommand c{in(r.p_min, r.p_max), in(r.v_min, r.v_max), in(0, r.kp_max), in(0, r.kd_max), in(r.t_min, r.t_max)};
      const std::array<std::uint8_t, 8> data = pack_command(quantise_command(c, r));
      ASSERT_EQ(classify(data), MitFrameKind::command);
      const MitCommand back = command_value(unpack_command(data), r);
      // Truncation: the decoded value is at or below the input, by less than one quantum (plus
      // single-precision rounding).
      EXPECT_NEAR(back.position, c.position - 0.5 * qp, 0.5 * qp + 1e-5 * r.p_max);
      EXPECT_NEAR(back.velocity, c.velocity - 0.5 * qv, 0.5 * qv + 1e-5 * r.v_max);
      EXPECT_NEAR(back.kp, c.kp - 0.5 * qkp, 0.5 * qkp + 1e-5 * r.kp_max);
      EXPECT_NEAR(back.kd, c.kd - 0.5 * qkd, 0.5 * qkd + 1e-5 * r.kd_max);
      EXPECT_NEAR(back.torque, c.torque - 0.5 * qt, 0.5 * qt + 1e-5 * r.t_max);
    }
  }
}

TEST(MitCodec, SeededReplyRoundTripsStayWithinOneQuantum) {
  const unsigned seed = 7031;
  SCOPED_TRACE(seed);
  std::mt19937 rng(seed);
  const MitRanges r = kHt04HeaderRanges;
  auto in = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
  for (int i = 0; i < 2000; ++i) {
    const auto id = static_cast<std::uint8_t>(rng() & 0xFF);
    const double p = in(r.p_min, r.p_max), v = in(r.v_min, r.v_max), t = in(r.t_min, r.t_max);
    MitReply back;
    ASSERT_TRUE(decode_reply(pack_reply(id, p, v, t, r), r, {}, &back));
    EXPECT_EQ(back.id, id);
    EXPECT_NEAR(back.position, p, (r.p_max - r.p_min) / 65535 + 1e-5 * r.p_max);
    EXPECT_NEAR(back.velocity, v, (r.v_max - r.v_min) / 4095 + 1e-5 * r.v_max);
    EXPECT_NEAR(back.torque, t, (r.t_max - r.t_min) / 4095 + 1e-5 * r.t_max);
  }
}

TEST(MitCodec, IntegersRoundTripThroughThePacking) {
  std::mt19937 rng(99);
  for (int i = 0; i < 1000; ++i) {
    const MitCommandBits b{static_cast<std::uint16_t>(rng() & 0xFFFF), static_cast<std::uint16_t>(rng() & 0xFFF),
                           static_cast<std::uint16_t>(rng() & 0xFFF), static_cast<std::uint16_t>(rng() & 0xFFF),
                           static_cast<std::uint16_t>(rng() & 0xFFF)};
    EXPECT_EQ(unpack_command(pack_command(b)), b);
  }
}

}  // namespace
}  // namespace avar::firmware_iface::mit
