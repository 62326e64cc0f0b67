// Golden frames from ../shared/protocols/odrive-cansimple.md, section 5 (vectors O1..O9), and
// encode/decode round trips over seeded random families.
#include "avar/firmware_iface/odrive_can_codec.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "avar/firmware_iface/actuator_link.hpp"

namespace avar::firmware_iface::odrive {
namespace {

using OdriveBytes = std::vector<std::uint8_t>;

CanFrame odrive_frame(std::uint32_t id, OdriveBytes bytes) { return can_data_frame(id, bytes); }

TEST(OdriveCanCodec, IdentifierIsNodeShiftedFiveOrCommand) {
  EXPECT_EQ(can_id(1, kSetInputPos), 0x2Cu);
  EXPECT_EQ(can_id(63, kClearErrors), 0x7F8u);
  EXPECT_EQ(odrive_node(0x7F8), 63);
  EXPECT_EQ(odrive_command(0x7F8), kClearErrors);
  EXPECT_EQ(can_id(64 + 2, kHeartbeat), can_id(2, kHeartbeat));  // node bits above 6 are dropped
}

TEST(OdriveCanCodec, O1_O2_Heartbeats) {
  Heartbeat h;
  ASSERT_TRUE(decode_heartbeat(odrive_frame(0x001, {0, 0, 0, 0, 1, 0, 0, 0}), HeartbeatLayout::v0_5, &h));
  EXPECT_EQ(odrive_node(0x001), 0);
  EXPECT_EQ(h.axis_error, 0u);
  EXPECT_TRUE(h.in_state(AxisState::idle));
  EXPECT_FALSE(h.motor_error || h.encoder_error || h.controller_error || h.trajectory_done);

  ASSERT_TRUE(decode_heartbeat(odrive_frame(0x021, {0, 0, 0, 0, 8, 0, 0, 0}), HeartbeatLayout::v0_5, &h));
  EXPECT_EQ(odrive_node(0x021), 1);
  EXPECT_TRUE(h.in_state(AxisState::closed_loop_control));

  Heartbeat idle;
  idle.state = 1;
  EXPECT_EQ(encode_heartbeat(0, idle), odrive_frame(0x001, {0, 0, 0, 0, 1, 0, 0, 0}));
  Heartbeat closed;
  closed.state = 8;
  EXPECT_EQ(encode_heartbeat(1, closed), odrive_frame(0x021, {0, 0, 0, 0, 8, 0, 0, 0}));
}

TEST(OdriveCanCodec, HeartbeatFlagsInBothLayouts) {
  Heartbeat h;
  ASSERT_TRUE(decode_heartbeat(odrive_frame(0x041, {0x40, 0, 0, 0, 1, 1, 1, 0x81}), HeartbeatLayout::v0_5, &h));
  EXPECT_EQ(h.axis_error, kMotorFailed);
  EXPECT_TRUE(h.motor_error && h.encoder_error && h.controller_error && h.trajectory_done);

  ASSERT_TRUE(decode_heartbeat(odrive_frame(0x041, {0, 0x40, 0, 0, 8, 3, 1, 0}), HeartbeatLayout::v0_6, &h));
  EXPECT_EQ(h.axis_error, 0x4000u);
  EXPECT_EQ(h.procedure_result, 3);
  EXPECT_TRUE(h.trajectory_done);
  EXPECT_FALSE(h.motor_error);
}

TEST(OdriveCanCodec, O3_O4_SetInputPos) {
  EXPECT_EQ(encode_set_input_pos(1, 1.0f), odrive_frame(0x02C, {0x00, 0x00, 0x80, 0x3F, 0, 0, 0, 0}));
  EXPECT_EQ(encode_set_input_pos(0, -2.5f, 1.5, 0.2), odrive_frame(0x00C, {0x00, 0x00, 0x20, 0xC0, 0xDC, 0x05, 0xC8, 0x00}));
  InputPos p;
  ASSERT_TRUE(decode_set_input_pos(odrive_frame(0x00C, {0x00, 0x00, 0x20, 0xC0, 0xDC, 0x05, 0xC8, 0x00}), &p));
  EXPECT_EQ(p.position, -2.5f);
  EXPECT_DOUBLE_EQ(p.vel_ff, 1.5);
  EXPECT_DOUBLE_EQ(p.torque_ff, 0.2);
}

TEST(OdriveCanCodec, InputPosFeedForwardRoundsAndSaturates) {
  auto raw = [](double vel_ff, double torque_ff) {
    const CanFrame f = encode_set_input_pos(0, 0.0f, vel_ff, torque_ff);
    return std::pair<int, int>(static_cast<std::int16_t>(f.data[4] | f.data[5] << 8),
                               static_cast<std::int16_t>(f.data[6] | f.data[7] << 8));
  };
  EXPECT_EQ(raw(0.0014, -0.0016), (std::pair<int, int>(1, -2)));
  EXPECT_EQ(raw(0.00151, -0.00151), (std::pair<int, int>(2, -2)));  // nearest, not truncated
  EXPECT_EQ(raw(40.0, -40.0), (std::pair<int, int>(32767, -32768)));
  EXPECT_EQ(raw(std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()), (std::pair<int, int>(0, 0)));
}

TEST(OdriveCanCodec, O5_O6_StateAndControllerModes) {
  EXPECT_EQ(encode_set_axis_state(1, AxisState::closed_loop_control), odrive_frame(0x027, {0x08, 0, 0, 0}));
  EXPECT_EQ(encode_set_controller_modes(1, ControlMode::position, InputMode::passthrough),
            odrive_frame(0x02B, {0x03, 0, 0, 0, 0x01, 0, 0, 0}));
  std::uint32_t state = 0;
  ASSERT_TRUE(decode_set_axis_state(odrive_frame(0x027, {0x08, 0, 0, 0}), &state));
  EXPECT_EQ(state, 8u);
  ControllerModes m;
  ASSERT_TRUE(decode_set_controller_modes(odrive_frame(0x02B, {0x03, 0, 0, 0, 0x01, 0, 0, 0}), &m));
  EXPECT_EQ(m.control_mode, 3);
  EXPECT_EQ(m.input_mode, 1);
}

TEST(OdriveCanCodec, O7_O8_InputVelAndLimits) {
  EXPECT_EQ(encode_set_input_vel(1, 2.0f), odrive_frame(0x02D, {0x00, 0x00, 0x00, 0x40, 0, 0, 0, 0}));
  EXPECT_EQ(encode_set_limits(1, 10.0f, 20.0f), odrive_frame(0x02F, {0x00, 0x00, 0x20, 0x41, 0x00, 0x00, 0xA0, 0x41}));
  Limits l;
  ASSERT_TRUE(decode_set_limits(odrive_frame(0x02F, {0x00, 0x00, 0x20, 0x41, 0x00, 0x00, 0xA0, 0x41}), &l));
  EXPECT_EQ(l.velocity_limit, 10.0f);
  EXPECT_EQ(l.current_limit, 20.0f);
}

TEST(OdriveCanCodec, O9_EncoderEstimatesRequestAndReply) {
  const CanFrame request = encode_get_encoder_estimates(1);
  EXPECT_EQ(request.id, 0x029u);
  EXPECT_TRUE(request.rtr);
  EXPECT_EQ(request.dlc, 8);
  EXPECT_FALSE(request.extended);
  EXPECT_TRUE(is_request(request, kGetEncoderEstimates));

  const CanFrame reply = odrive_frame(0x029, {0x00, 0x00, 0x80, 0x3E, 0x00, 0x00, 0x80, 0xBF});
  EncoderEstimates e;
  ASSERT_TRUE(decode_encoder_estimates(reply, &e));
  EXPECT_EQ(e.position, 0.25f);
  EXPECT_EQ(e.velocity, -1.0f);
  EXPECT_EQ(encode_encoder_estimates(1, 0.25f, -1.0f), reply);
  EXPECT_FALSE(decode_encoder_estimates(request, &e));  // the request is no answer
}

TEST(OdriveCanCodec, CommandsWithoutData) {
  const CanFrame estop = encode_estop(2);
  EXPECT_EQ(estop, odrive_frame(0x042, {}));
  EXPECT_TRUE(is_command(estop, kEstop));
  const CanFrame clear = encode_clear_errors(2);
  EXPECT_EQ(clear, odrive_frame(0x058, {}));
  EXPECT_TRUE(is_command(clear, kClearErrors));
  EXPECT_FALSE(is_command(clear, kEstop));
  EXPECT_FALSE(is_request(clear, kClearErrors));
}

TEST(OdriveCanCodec, TorqueAndMotorError) {
  EXPECT_EQ(encode_set_input_torque(3, 0.5f), odrive_frame(0x06E, {0x00, 0x00, 0x00, 0x3F}));
  float torque = 0;
  ASSERT_TRUE(decode_set_input_torque(odrive_frame(0x06E, {0x00, 0x00, 0x00, 0x3F}), &torque));
  EXPECT_EQ(torque, 0.5f);
  const CanFrame motor = encode_motor_error(3, 0x0000000100000800ull);
  EXPECT_EQ(motor, odrive_frame(0x063, {0x00, 0x08, 0, 0, 0x01, 0, 0, 0}));
  std::uint64_t e = 0;
  ASSERT_TRUE(decode_motor_error(motor, &e));
  EXPECT_EQ(e, 0x0000000100000800ull);
  EXPECT_TRUE(encode_get_motor_error(3).rtr);
}

TEST(OdriveCanCodec, DecodersRefuseMalformedFrames) {
  Heartbeat h;
  EXPECT_FALSE(decode_heartbeat(odrive_frame(0x021, {0, 0, 0, 0, 8}), HeartbeatLayout::v0_5, &h));  // short
  CanFrame extended = odrive_frame(0x021, {0, 0, 0, 0, 8, 0, 0, 0});
  extended.extended = true;
  EXPECT_FALSE(decode_heartbeat(extended, HeartbeatLayout::v0_5, &h));
  EXPECT_FALSE(decode_heartbeat(can_remote_frame(0x021, 8), HeartbeatLayout::v0_5, &h));
  EXPECT_FALSE(decode_heartbeat(odrive_frame(0x029, {0, 0, 0, 0, 8, 0, 0, 0}), HeartbeatLayout::v0_5, &h));  // other command
  CanFrame error = odrive_frame(0x021, {0, 0, 0, 0, 8, 0, 0, 0});
  error.error = true;
  EXPECT_FALSE(decode_heartbeat(error, HeartbeatLayout::v0_5, &h));
  EncoderEstimates e;
  EXPECT_FALSE(decode_encoder_estimates(odrive_frame(0x029, {0, 0, 0x80, 0x3E}), &e));
  InputPos p;
  EXPECT_FALSE(decode_set_input_pos(odrive_frame(0x02C, {0, 0, 0x80, 0x3F, 0, 0}), &p));
  std::uint32_t state = 0;
  EXPECT_FALSE(decode_set_axis_state(odrive_frame(0x027, {8, 0}), &state));
}

TEST(OdriveCanCodec, NamesOfStatesAndErrors) {
  EXPECT_STREQ(axis_state_name(8), "CLOSED_LOOP_CONTROL");
  EXPECT_STREQ(axis_state_name(1), "IDLE");
  EXPECT_STREQ(axis_state_name(99), "UNKNOWN");
  EXPECT_EQ(describe_axis_state(99), "state 99");
  EXPECT_EQ(describe_axis_error(0), "none");
  EXPECT_EQ(describe_axis_error(kMotorFailed), "motor failed");
  EXPECT_EQ(describe_axis_error(kInvalidState | kEstopRequested | 0x80000u), "invalid state, estop requested, 0x80000");
  for (std::uint32_t bit = 1; bit <= kHomingWithoutEndstop; bit <<= 1) EXPECT_NE(axis_error_name(bit), nullptr) << bit;
  EXPECT_EQ(axis_error_name(0x40000), nullptr);
}

TEST(OdriveCanCodec, AxisErrorsMapToDeviceFaults) {
  EXPECT_EQ(axis_error_faults(0), 0u);
  EXPECT_EQ(axis_error_faults(kDcBusUnderVoltage), kDeviceVoltage);
  EXPECT_EQ(axis_error_faults(kMotorFailed), kDeviceElectrical);
  EXPECT_EQ(axis_error_faults(kEncoderFailed), kDeviceEncoder);
  EXPECT_EQ(axis_error_faults(kEstopRequested), kDeviceOther);
  EXPECT_EQ(axis_error_faults(kDcBusOverVoltage | kEncoderFailed), kDeviceVoltage | kDeviceEncoder);
  EXPECT_EQ(axis_error_faults(0x80000000u), kDeviceOther);  // unknown bits are still a fault
}

TEST(OdriveCanCodec, RandomRoundTrips) {
  const unsigned seed = 0x0D21;
  std::mt19937 rng(seed);
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::uniform_real_distribution<float> any_float(-1e4f, 1e4f);
  std::uniform_real_distribution<double> ff(-32.767, 32.767);
  std::uniform_int_distribution<int> node_of(0, kMaxNode);
  std::uniform_int_distribution<std::uint32_t> u32;
  std::uniform_int_distribution<int> byte(0, 255);
  for (int i = 0; i < 2000; ++i) {
    const auto node = static_cast<std::uint8_t>(node_of(rng));

    const float pos = any_float(rng);
    const double vel_ff = ff(rng), torque_ff = ff(rng);
    CanFrame f = encode_set_input_pos(node, pos, vel_ff, torque_ff);
    ASSERT_EQ(odrive_node(f.id), node);
    InputPos p;
    ASSERT_TRUE(decode_set_input_pos(f, &p));
    EXPECT_EQ(p.position, pos);
    EXPECT_NEAR(p.vel_ff, vel_ff, 0.0005 + 1e-12);
    EXPECT_NEAR(p.torque_ff, torque_ff, 0.0005 + 1e-12);

    const float a = any_float(rng), b = any_float(rng);
    EncoderEstimates e;
    ASSERT_TRUE(decode_encoder_estimates(encode_encoder_estimates(node, a, b), &e));
    EXPECT_EQ(e.position, a);
    EXPECT_EQ(e.velocity, b);
    Limits l;
    ASSERT_TRUE(decode_set_limits(encode_set_limits(node, a, b), &l));
    EXPECT_EQ(l.velocity_limit, a);
    EXPECT_EQ(l.current_limit, b);
    float v = 0, t = 0;
    ASSERT_TRUE(decode_set_input_vel(encode_set_input_vel(node, a, b), &v, &t));
    EXPECT_EQ(v, a);
    EXPECT_EQ(t, b);
    ASSERT_TRUE(decode_set_input_torque(encode_set_input_torque(node, a), &t));
    EXPECT_EQ(t, a);

    ControllerModes m;
    const auto control = static_cast<ControlMode>(byte(rng) % 4);
    const auto input = static_cast<InputMode>(byte(rng) % 8);
    ASSERT_TRUE(decode_set_controller_modes(encode_set_controller_modes(node, control, input), &m));
    EXPECT_EQ(m.control_mode, static_cast<std::int32_t>(control));
    EXPECT_EQ(m.input_mode, static_cast<std::int32_t>(input));
    std::uint32_t state = 0;
    const auto s = static_cast<AxisState>(byte(rng) % 14);
    ASSERT_TRUE(decode_set_axis_state(encode_set_axis_state(node, s), &state));
    EXPECT_EQ(state, static_cast<std::uint32_t>(s));

    Heartbeat h;
    h.axis_error = u32(rng);
    h.state = static_cast<std::uint8_t>(byte(rng));
    h.motor_error = byte(rng) & 1;
    h.encoder_error = byte(rng) & 1;
    h.controller_error = byte(rng) & 1;
    h.trajectory_done = byte(rng) & 1;
    Heartbeat back;
    ASSERT_TRUE(decode_heartbeat(encode_heartbeat(node, h, HeartbeatLayout::v0_5), HeartbeatLayout::v0_5, &back));
    EXPECT_EQ(back.axis_error, h.axis_error);
    EXPECT_EQ(back.state, h.state);
    EXPECT_EQ(back.motor_error, h.motor_error);
    EXPECT_EQ(back.encoder_error, h.encoder_error);
    EXPECT_EQ(back.controller_error, h.controller_error);
    EXPECT_EQ(back.trajectory_done, h.trajectory_done);
    Heartbeat h6;
    h6.axis_error = h.axis_error;
    h6.state = h.state;
    h6.procedure_result = static_cast<std::uint8_t>(byte(rng));
    h6.trajectory_done = h.trajectory_done;
    ASSERT_TRUE(decode_heartbeat(encode_heartbeat(node, h6, HeartbeatLayout::v0_6), HeartbeatLayout::v0_6, &back));
    EXPECT_EQ(back.axis_error, h6.axis_error);
    EXPECT_EQ(back.state, h6.state);
    EXPECT_EQ(back.procedure_result, h6.procedure_result);
    EXPECT_EQ(back.trajectory_done, h6.trajectory_done);

    const std::uint64_t motor = static_cast<std::uint64_t>(u32(rng)) << 32 | u32(rng);
    std::uint64_t motor_back = 0;
    ASSERT_TRUE(decode_motor_error(encode_motor_error(node, motor), &motor_back));
    EXPECT_EQ(motor_back, motor);
  }
}

}  // namespace
}  // namespace avar::firmware_iface::odrive
