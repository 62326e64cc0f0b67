// The simulated MIT-mode motor answers as the bgkatz firmware does (notes
// ../shared/protocols/mit-cheetah-can.md): modes, replies to every accepted frame, set zero, the
// command timeout, the impedance law on quantised commands, and its fault hooks.
#include "avar/sim/sim_mit_motor.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace avar::sim {
namespace {

namespace mit = firmware_iface::mit;
using firmware_iface::CanFrame;
using MitBytes = std::vector<std::uint8_t>;

SimMitMotorConfig mit_sim_config(double initial_position = 0) {
  SimMitMotorConfig c;
  c.id = 3;
  c.master_id = 0;
  c.initial_position = initial_position;
  return c;
}

std::vector<CanFrame> mit_sim_replies(SimMitMotor& m) {
  std::vector<CanFrame> out;
  CanFrame f;
  while (m.peek_transmit(&f)) {
    out.push_back(f);
    m.pop_transmit();
  }
  return out;
}

void mit_sim_run(SimMitMotor& m, double seconds) {
  for (double t = 0; t < seconds; t += 0.001) m.advance(0.001);
}

mit::MitReply mit_sim_decode(const CanFrame& f) {
  mit::MitReply r;
  EXPECT_TRUE(mit::decode_reply(f.payload(), mit::kMiniCheetahRanges, {}, &r));
  return r;
}

CanFrame mit_sim_hold(double position, double kp = 20, double kd = 0.5) {
  return mit::command_frame(3, {position, 0, kp, kd, 0}, mit::kMiniCheetahRanges);
}

TEST(SimMitMotor, StartsInMenuModeAndEveryAcceptedFrameIsAnswered) {
  SimMitMotor m(mit_sim_config(0.25));
  EXPECT_FALSE(m.motor_mode());
  m.receive(mit_sim_hold(1.0));  // a command in menu mode: answered, not applied
  const std::vector<CanFrame> r = mit_sim_replies(m);
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].id, 0u);
  EXPECT_FALSE(r[0].extended);
  EXPECT_EQ(r[0].dlc, 6);
  EXPECT_EQ(r[0].data[0], 3);
  EXPECT_NEAR(mit_sim_decode(r[0]).position, 0.25, 1e-3);
  mit_sim_run(m, 0.2);
  EXPECT_FALSE(m.driving());
  EXPECT_DOUBLE_EQ(m.position(), 0.25);
  EXPECT_EQ(m.replies_sent(), 1u);
}

TEST(SimMitMotor, K6_EnterMotorModeHoldsNoTorqueUntilTheFirstCommand) {
  SimMitMotor m(mit_sim_config(0.5));
  m.receive(firmware_iface::can_data_frame(3, MitBytes{0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFC}));
  EXPECT_TRUE(m.motor_mode());
  ASSERT_EQ(mit_sim_replies(m).size(), 1u);
  EXPECT_EQ(m.command().kp, 0);
  mit_sim_run(m, 0.1);
  EXPECT_DOUBLE_EQ(m.position(), 0.5);
  EXPECT_EQ(m.torque(), 0);
}

TEST(SimMitMotor, K2_CommandIsDecodedAsTheFirmwareDoesAndTracked) {
  SimMitMotor m(mit_sim_config());
  m.receive(mit::special_frame(3, mit::MitFrameKind::enter_motor_mode));
  m.receive(firmware_iface::can_data_frame(3, MitBytes{0x8A, 0x3C, 0x7F, 0xF0, 0xA3, 0x19, 0x97, 0xFF}));
  // Quantisation is real: 35388, 163, 409 decode below 1.0, 20, 0.5.
  EXPECT_FLOAT_EQ(static_cast<float>(m.command().position), static_cast<float>(mit::uint_to_float(35388, -12.5, 12.5, 16)));
  EXPECT_LT(m.command().position, 1.0);
  EXPECT_LT(m.command().kp, 20.0);
  EXPECT_LT(m.command().kd, 0.5);
  EXPECT_LT(m.command().velocity, 0.0);  // 2047: slightly below zero
  mit_sim_run(m, 0.05);
  m.receive(mit_sim_hold(1.0));  // within the timeout
  mit_sim_run(m, 0.09);
  EXPECT_TRUE(m.driving());
  EXPECT_NEAR(m.position(), m.command().position, 0.005);
  m.receive(mit_sim_hold(1.0));
  const std::vector<CanFrame> r = mit_sim_replies(m);
  ASSERT_EQ(r.size(), 4u);
  EXPECT_NEAR(mit_sim_decode(r.back()).position, 1.0, 0.005);
}

TEST(SimMitMotor, ExitMotorModeGoesLimp) {
  SimMitMotor m(mit_sim_config());
  m.receive(mit::special_frame(3, mit::MitFrameKind::enter_motor_mode));
  m.receive(mit_sim_hold(0.0, 100, 1));
  m.model().set_external_torque(1.0);
  mit_sim_run(m, 0.05);
  EXPECT_NEAR(m.position(), 0, 0.02);  // held against the load
  m.receive(mit::special_frame(3, mit::MitFrameKind::exit_motor_mode));
  EXPECT_FALSE(m.motor_mode());
  mit_sim_run(m, 0.05);
  EXPECT_EQ(m.torque(), 0);
  const std::vector<CanFrame> r = mit_sim_replies(m);
  ASSERT_EQ(r.size(), 3u);
  EXPECT_NEAR(mit_sim_decode(r[1]).torque, 0, 0.01);  // reply to the command, before any motion
  EXPECT_NEAR(mit_sim_decode(r[2]).torque, 0, 0.01);  // limp
}

TEST(SimMitMotor, SetZeroMakesThePresentPositionZeroInMenuModeOnly) {
  SimMitMotorConfig c = mit_sim_config(2.0);
  c.command_timeout_s = 0;  // no timeout: one command holds
  SimMitMotor m(c);
  m.receive(mit::special_frame(3, mit::MitFrameKind::set_zero));
  EXPECT_DOUBLE_EQ(m.position(), 0);
  std::vector<CanFrame> r = mit_sim_replies(m);
  ASSERT_EQ(r.size(), 1u);
  EXPECT_NEAR(mit_sim_decode(r[0]).position, 0, 1e-3);
  // In motor mode the zero stays where it is (answered all the same).
  m.receive(mit::special_frame(3, mit::MitFrameKind::enter_motor_mode));
  m.receive(mit_sim_hold(0.5));
  mit_sim_run(m, 0.3);
  m.receive(mit::special_frame(3, mit::MitFrameKind::set_zero));
  EXPECT_NEAR(m.position(), 0.5, 0.01);
  EXPECT_EQ(mit_sim_replies(m).size(), 3u);
}

TEST(SimMitMotor, CommandTimeoutRemovesTorqueUntilTheNextCommand) {
  SimMitMotorConfig c = mit_sim_config();
  c.command_timeout_s = 0.02;
  SimMitMotor m(c);
  m.receive(mit::special_frame(3, mit::MitFrameKind::enter_motor_mode));
  m.receive(mit_sim_hold(0.0, 100, 1));
  m.model().set_external_torque(0.5);
  mit_sim_run(m, 0.015);
  EXPECT_TRUE(m.driving());
  mit_sim_run(m, 0.01);
  EXPECT_FALSE(m.driving());
  EXPECT_TRUE(m.motor_mode());
  EXPECT_EQ(m.torque(), 0);
  m.receive(mit_sim_hold(0.0, 100, 1));
  EXPECT_TRUE(m.driving());
  mit_sim_run(m, 0.01);
  EXPECT_NE(m.torque(), 0);
}

TEST(SimMitMotor, FramesOfWrongLengthOrForOthersAreIgnored) {
  SimMitMotor m(mit_sim_config());
  const MitBytes enter{0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFC};
  m.receive(firmware_iface::can_data_frame(3, std::span(enter).first(7)));
  m.receive(firmware_iface::can_data_frame(3, std::span(enter).first(6)));
  m.receive(firmware_iface::can_data_frame(4, enter));
  m.receive(firmware_iface::can_data_frame(3, enter, /*extended=*/true));
  m.receive(firmware_iface::can_remote_frame(3, 8));
  EXPECT_FALSE(m.motor_mode());
  EXPECT_EQ(m.frames_accepted(), 0u);
  EXPECT_TRUE(mit_sim_replies(m).empty());
}

TEST(SimMitMotor, ASilencedMotorStillObeysButSendsNothing) {
  SimMitMotor m(mit_sim_config());
  m.set_answering(false);
  m.receive(mit::special_frame(3, mit::MitFrameKind::enter_motor_mode));
  m.receive(mit_sim_hold(0.3));
  mit_sim_run(m, 0.08);
  EXPECT_TRUE(mit_sim_replies(m).empty());
  EXPECT_EQ(m.frames_accepted(), 2u);
  EXPECT_NEAR(m.position(), 0.3, 0.02);
  m.set_answering(true);
  m.receive(mit_sim_hold(0.3));
  EXPECT_EQ(mit_sim_replies(m).size(), 1u);
}

TEST(SimMitMotor, CloneRepliesAreEightBytesWithTheSameFirstSix) {
  SimMitMotorConfig c = mit_sim_config(-1.0);
  c.reply_length = 8;
  c.master_id = 0x100;
  SimMitMotor m(c);
  m.receive(mit_sim_hold(0));
  const std::vector<CanFrame> r = mit_sim_replies(m);
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].id, 0x100u);
  EXPECT_EQ(r[0].dlc, 8);
  EXPECT_NEAR(mit_sim_decode(r[0]).position, -1.0, 1e-3);
}

TEST(SimMitMotor, ReplyReportsTheTorqueHoldingALoad) {
  SimMitMotor m(mit_sim_config());
  m.receive(mit::special_frame(3, mit::MitFrameKind::enter_motor_mode));
  m.receive(mit_sim_hold(0.0, 200, 2));
  m.model().set_external_torque(4.0);
  mit_sim_run(m, 0.09);
  m.receive(mit_sim_hold(0.0, 200, 2));
  const std::vector<CanFrame> r = mit_sim_replies(m);
  EXPECT_NEAR(mit_sim_decode(r.back()).torque, 4.0, 0.1);
  EXPECT_NEAR(mit_sim_decode(r.back()).position, -0.02, 0.005);  // kp·e = 4 N·m
}

TEST(SimMitMotor, RejectsBadConfig) {
  SimMitMotorConfig c = mit_sim_config();
  c.master_id = 3;
  EXPECT_THROW(SimMitMotor{c}, std::invalid_argument);
  c = mit_sim_config();
  c.reply_length = 5;
  EXPECT_THROW(SimMitMotor{c}, std::invalid_argument);
  c = mit_sim_config();
  c.ranges.kp_max = 0;
  EXPECT_THROW(SimMitMotor{c}, std::invalid_argument);
}

}  // namespace
}  // namespace avar::sim
