// The simulated ODrive axis answers as firmware 0.5.x does: golden frames from the protocol
// notes (O1, O2, O9), every state transition, the cyclic messages, the input modes and limits.
#include "avar/sim/sim_odrive_axis.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "avar/firmware_iface/odrive_can_codec.hpp"

namespace avar::sim {
namespace {

namespace od = firmware_iface::odrive;
using firmware_iface::can_data_frame;
using firmware_iface::can_remote_frame;
using firmware_iface::CanFrame;

std::vector<CanFrame> odrive_sim_drain(SimOdriveAxis& axis) {
  std::vector<CanFrame> out;
  CanFrame f;
  while (axis.peek_transmit(&f)) {
    out.push_back(f);
    axis.pop_transmit();
  }
  return out;
}

/// Advances in 1 ms steps (as a bus would), dropping what the axis sends.
void odrive_sim_run(SimOdriveAxis& axis, double seconds) {
  for (int i = 0; i < static_cast<int>(std::lround(seconds * 1000)); ++i) {
    axis.advance(0.001);
    odrive_sim_drain(axis);
  }
}

od::Heartbeat odrive_sim_heartbeat(SimOdriveAxis& axis, std::uint8_t node,
                                   od::HeartbeatLayout layout = od::HeartbeatLayout::v0_5) {
  odrive_sim_drain(axis);
  for (int i = 0; i < 200; ++i) {
    axis.advance(0.001);
    for (const CanFrame& f : odrive_sim_drain(axis))
      if (od::Heartbeat h; f.id == od::can_id(node, od::kHeartbeat) && od::decode_heartbeat(f, layout, &h)) return h;
  }
  ADD_FAILURE() << "no heartbeat from node " << int(node);
  return {};
}

SimOdriveAxisConfig odrive_sim_config(std::uint8_t node = 1) {
  SimOdriveAxisConfig c;
  c.node = node;
  return c;
}

constexpr std::uint8_t kIdle = 1, kClosedLoop = 8;

TEST(SimOdriveAxis, O1_IdleHeartbeatEvery100ms) {
  SimOdriveAxis axis(odrive_sim_config(0));
  std::vector<CanFrame> frames;
  for (int i = 0; i < 1000; ++i) {
    axis.advance(0.001);
    for (const CanFrame& f : odrive_sim_drain(axis)) frames.push_back(f);
  }
  ASSERT_EQ(frames.size(), 10u);
  EXPECT_EQ(frames[0], can_data_frame(0x001, std::vector<std::uint8_t>{0, 0, 0, 0, 1, 0, 0, 0}));
  EXPECT_EQ(axis.heartbeats_sent(), 10u);
}

TEST(SimOdriveAxis, O2_ClosedLoopOnRequestAndBackToIdle) {
  SimOdriveAxis axis(odrive_sim_config(1));
  axis.receive(od::encode_set_axis_state(1, od::AxisState::closed_loop_control));
  EXPECT_EQ(axis.state(), kClosedLoop);
  odrive_sim_drain(axis);
  axis.advance(0.1);
  const auto frames = odrive_sim_drain(axis);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0], can_data_frame(0x021, std::vector<std::uint8_t>{0, 0, 0, 0, 8, 0, 0, 0}));
  axis.receive(od::encode_set_axis_state(1, od::AxisState::idle));
  EXPECT_EQ(axis.state(), kIdle);
  EXPECT_EQ(axis.axis_error(), 0u);
}

TEST(SimOdriveAxis, ClosedLoopEntryTakesItsTimeAndIdleCancelsIt) {
  SimOdriveAxisConfig c = odrive_sim_config();
  c.closed_loop_entry_s = 0.5;
  SimOdriveAxis axis(c);
  axis.receive(od::encode_set_axis_state(1, od::AxisState::closed_loop_control));
  odrive_sim_run(axis, 0.3);
  EXPECT_EQ(odrive_sim_heartbeat(axis, 1).state, kIdle);
  odrive_sim_run(axis, 0.2);
  EXPECT_EQ(axis.state(), kClosedLoop);

  axis.receive(od::encode_set_axis_state(1, od::AxisState::idle));
  axis.receive(od::encode_set_axis_state(1, od::AxisState::closed_loop_control));
  odrive_sim_run(axis, 0.2);
  axis.receive(od::encode_set_axis_state(1, od::AxisState::idle));
  odrive_sim_run(axis, 0.5);
  EXPECT_EQ(axis.state(), kIdle);
}

TEST(SimOdriveAxis, UncalibratedAxisRefusesClosedLoopWithInvalidState) {
  SimOdriveAxisConfig c = odrive_sim_config();
  c.calibrated = false;
  SimOdriveAxis axis(c);
  axis.receive(od::encode_set_axis_state(1, od::AxisState::closed_loop_control));
  EXPECT_EQ(axis.state(), kIdle);
  EXPECT_EQ(axis.axis_error(), od::kInvalidState);
  const od::Heartbeat h = odrive_sim_heartbeat(axis, 1);
  EXPECT_EQ(h.axis_error, od::kInvalidState);
  EXPECT_EQ(h.state, kIdle);

  axis.receive(od::encode_clear_errors(1));
  EXPECT_EQ(axis.axis_error(), 0u);
  axis.set_calibrated(true);
  axis.receive(od::encode_set_axis_state(1, od::AxisState::closed_loop_control));
  EXPECT_EQ(axis.state(), kClosedLoop);
}

TEST(SimOdriveAxis, UnsupportedStatesAreInvalidAndDisarm) {
  for (od::AxisState s : {od::AxisState::full_calibration_sequence, od::AxisState::homing, od::AxisState::undefined}) {
    SimOdriveAxis axis(odrive_sim_config());
    axis.receive(od::encode_set_axis_state(1, od::AxisState::closed_loop_control));
    axis.receive(od::encode_set_axis_state(1, s));
    EXPECT_EQ(axis.state(), kIdle);
    EXPECT_EQ(axis.axis_error(), od::kInvalidState);
  }
  SimOdriveAxis axis(odrive_sim_config());
  CanFrame request = od::encode_set_axis_state(1, od::AxisState::idle);
  request.data[0] = 42;
  axis.receive(request);
  EXPECT_EQ(axis.axis_error(), od::kInvalidState);
}

TEST(SimOdriveAxis, EstopLatchesUntilClearErrors) {
  SimOdriveAxis axis(odrive_sim_config(2));
  axis.receive(od::encode_set_axis_state(2, od::AxisState::closed_loop_control));
  axis.receive(od::encode_estop(2));
  EXPECT_EQ(axis.state(), kIdle);
  EXPECT_EQ(axis.axis_error(), od::kEstopRequested);
  axis.receive(od::encode_set_axis_state(2, od::AxisState::closed_loop_control));
  EXPECT_EQ(axis.state(), kIdle);  // a latched error keeps it disarmed
  EXPECT_EQ(axis.axis_error(), od::kEstopRequested);
  axis.receive(od::encode_clear_errors(2));
  axis.receive(od::encode_set_axis_state(2, od::AxisState::closed_loop_control));
  EXPECT_EQ(axis.state(), kClosedLoop);
}

TEST(SimOdriveAxis, InjectedErrorDisarmsAndShowsInHeartbeat) {
  SimOdriveAxis axis(odrive_sim_config());
  axis.receive(od::encode_set_axis_state(1, od::AxisState::closed_loop_control));
  axis.inject_axis_error(od::kMotorFailed, 0x800);
  EXPECT_EQ(axis.state(), kIdle);
  const od::Heartbeat h = odrive_sim_heartbeat(axis, 1);
  EXPECT_EQ(h.axis_error, od::kMotorFailed);
  EXPECT_TRUE(h.motor_error);
  axis.receive(od::encode_get_motor_error(1));
  const auto frames = odrive_sim_drain(axis);
  ASSERT_EQ(frames.size(), 1u);
  std::uint64_t motor_error = 0;
  ASSERT_TRUE(od::decode_motor_error(frames[0], &motor_error));
  EXPECT_EQ(motor_error, 0x800u);
}

TEST(SimOdriveAxis, O9_EncoderEstimatesOnRequestAndCyclic) {
  SimOdriveAxis axis(odrive_sim_config(1));
  axis.set_position_turns(0.25);
  axis.receive(od::encode_get_encoder_estimates(1));
  auto frames = odrive_sim_drain(axis);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0], can_data_frame(0x029, std::vector<std::uint8_t>{0x00, 0x00, 0x80, 0x3E, 0, 0, 0, 0}));

  axis.set_answers_requests(false);
  axis.receive(od::encode_get_encoder_estimates(1));
  EXPECT_TRUE(odrive_sim_drain(axis).empty());

  SimOdriveAxisConfig c = odrive_sim_config(1);
  c.encoder_period_s = 0.01;
  c.heartbeat_period_s = 0;
  SimOdriveAxis cyclic(c);
  int estimates = 0;
  for (int i = 0; i < 100; ++i) {
    cyclic.advance(0.001);
    for (const CanFrame& f : odrive_sim_drain(cyclic)) estimates += f.id == 0x029;
  }
  EXPECT_EQ(estimates, 10);
}

TEST(SimOdriveAxis, HeartbeatCanBeStoppedAndResumed) {
  SimOdriveAxis axis(odrive_sim_config());
  axis.set_heartbeat_enabled(false);
  odrive_sim_run(axis, 0.5);
  EXPECT_EQ(axis.heartbeats_sent(), 0u);
  axis.set_heartbeat_enabled(true);
  odrive_sim_run(axis, 0.2);
  EXPECT_EQ(axis.heartbeats_sent(), 2u);
}

TEST(SimOdriveAxis, V06HeartbeatLayout) {
  SimOdriveAxisConfig c = odrive_sim_config(3);
  c.heartbeat_layout = od::HeartbeatLayout::v0_6;
  SimOdriveAxis axis(c);
  axis.receive(od::encode_set_axis_state(3, od::AxisState::closed_loop_control));
  odrive_sim_drain(axis);
  axis.advance(0.1);
  const auto frames = odrive_sim_drain(axis);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0], can_data_frame(0x061, std::vector<std::uint8_t>{0, 0, 0, 0, 8, 0, 0, 0}));
}

TEST(SimOdriveAxis, IgnoresOtherNodesAndMalformedFrames) {
  SimOdriveAxis axis(odrive_sim_config(1));
  axis.receive(od::encode_set_axis_state(2, od::AxisState::closed_loop_control));  // another node
  CanFrame extended = od::encode_set_axis_state(1, od::AxisState::closed_loop_control);
  extended.extended = true;
  axis.receive(extended);
  CanFrame short_frame = od::encode_set_axis_state(1, od::AxisState::closed_loop_control);
  short_frame.dlc = 2;
  axis.receive(short_frame);
  axis.receive(can_remote_frame(od::can_id(1, od::kSetAxisRequestedState), 4));
  CanFrame error = od::encode_set_axis_state(1, od::AxisState::closed_loop_control);
  error.error = true;
  axis.receive(error);
  axis.receive(od::encode_get_encoder_estimates(2));
  CanFrame short_pos = od::encode_set_input_pos(1, 5.0f);
  short_pos.dlc = 4;
  axis.receive(short_pos);
  EXPECT_EQ(axis.state(), kIdle);
  EXPECT_EQ(axis.axis_error(), 0u);
  EXPECT_EQ(axis.input_pos(), 0.0);
  EXPECT_EQ(axis.frames_received(), 0u);
  EXPECT_TRUE(odrive_sim_drain(axis).empty());
}

TEST(SimOdriveAxis, ModesAndLimitsAreStored) {
  SimOdriveAxis axis(odrive_sim_config());
  axis.receive(od::encode_set_controller_modes(1, od::ControlMode::position, od::InputMode::pos_filter));
  axis.receive(od::encode_set_limits(1, 3.0f, 7.0f));
  EXPECT_EQ(axis.input_mode(), 3);
  EXPECT_EQ(axis.control_mode(), 3);
  EXPECT_EQ(axis.velocity_limit(), 3.0);
  EXPECT_EQ(axis.current_limit(), 7.0);
  CanFrame bad_mode = od::encode_set_controller_modes(1, od::ControlMode::position, od::InputMode::passthrough);
  bad_mode.data[4] = 99;
  axis.receive(bad_mode);
  EXPECT_EQ(axis.input_mode(), 3);
  axis.receive(od::encode_set_limits(1, -1.0f, 7.0f));
  EXPECT_EQ(axis.velocity_limit(), 3.0);
}

TEST(SimOdriveAxis, EnteringClosedLoopHoldsThePresentPosition) {
  SimOdriveAxisConfig c = odrive_sim_config();
  c.initial_position_turns = 0.7;
  SimOdriveAxis axis(c);
  axis.receive(od::encode_set_axis_state(1, od::AxisState::closed_loop_control));
  EXPECT_NEAR(axis.input_pos(), 0.7, 1e-12);
  odrive_sim_run(axis, 0.3);
  EXPECT_NEAR(axis.position_turns(), 0.7, 1e-6);

  // Without the firmware's hold, the axis goes where input_pos says (0 here): a jump.
  c.hold_position_on_entry = false;
  SimOdriveAxis raw(c);
  raw.receive(od::encode_set_axis_state(1, od::AxisState::closed_loop_control));
  odrive_sim_run(raw, 1.0);
  EXPECT_NEAR(raw.position_turns(), 0.0, 1e-3);
}

TEST(SimOdriveAxis, PassthroughReachesTheGoalWithinVelocityAndCurrentLimits) {
  SimOdriveAxis axis(odrive_sim_config());
  axis.receive(od::encode_set_limits(1, 1.5f, 20.0f));
  axis.receive(od::encode_set_axis_state(1, od::AxisState::closed_loop_control));
  axis.receive(od::encode_set_input_pos(1, 1.0f));
  double peak_velocity = 0, peak_torque = 0;
  for (int i = 0; i < 1500; ++i) {
    axis.advance(0.001);
    odrive_sim_drain(axis);
    peak_velocity = std::max(peak_velocity, std::abs(axis.velocity_turns_per_s()));
    peak_torque = std::max(peak_torque, std::abs(axis.motor().torque()));
  }
  EXPECT_NEAR(axis.position_turns(), 1.0, 1e-3);
  EXPECT_LE(peak_velocity, 1.5 * 1.02);
  EXPECT_GT(peak_velocity, 1.4);
  EXPECT_LE(peak_torque, 20 * 0.04 + 1e-9);

  // A low current limit caps the torque: the move takes longer.
  SimOdriveAxis weak(odrive_sim_config());
  weak.receive(od::encode_set_limits(1, 1.5f, 1.0f));
  weak.receive(od::encode_set_axis_state(1, od::AxisState::closed_loop_control));
  weak.receive(od::encode_set_input_pos(1, 1.0f));
  double weak_peak = 0;
  for (int i = 0; i < 100; ++i) {
    weak.advance(0.001);
    weak_peak = std::max(weak_peak, std::abs(weak.motor().torque()));
  }
  EXPECT_LE(weak_peak, 0.04 + 1e-9);
  EXPECT_LT(weak.position_turns(), axis.position_turns());
}

TEST(SimOdriveAxis, PosFilterSmoothsAStep) {
  SimOdriveAxisConfig c = odrive_sim_config();
  c.input_filter_bandwidth = 10;
  SimOdriveAxis axis(c);
  axis.receive(od::encode_set_controller_modes(1, od::ControlMode::position, od::InputMode::pos_filter));
  axis.receive(od::encode_set_limits(1, 10.0f, 20.0f));
  axis.receive(od::encode_set_axis_state(1, od::AxisState::closed_loop_control));
  axis.receive(od::encode_set_input_pos(1, 1.0f));
  odrive_sim_run(axis, 0.05);
  const double early = axis.position_turns();
  EXPECT_GT(early, 0.0);
  EXPECT_LT(early, 0.2);  // passthrough would be most of the way there
  odrive_sim_run(axis, 1.5);
  EXPECT_NEAR(axis.position_turns(), 1.0, 5e-3);
}

TEST(SimOdriveAxis, TrapTrajCruisesAtItsVelocityAndReportsDone) {
  SimOdriveAxisConfig c = odrive_sim_config();
  c.trap_vel_limit = 1.0;
  c.trap_accel_limit = 4.0;
  c.trap_decel_limit = 4.0;
  SimOdriveAxis axis(c);
  axis.receive(od::encode_set_controller_modes(1, od::ControlMode::position, od::InputMode::trap_traj));
  axis.receive(od::encode_set_limits(1, 5.0f, 20.0f));
  axis.receive(od::encode_set_axis_state(1, od::AxisState::closed_loop_control));
  axis.receive(od::encode_set_input_pos(1, 2.0f));
  EXPECT_FALSE(odrive_sim_heartbeat(axis, 1).trajectory_done);
  double peak = 0;
  for (int i = 0; i < 2600; ++i) {
    axis.advance(0.001);
    odrive_sim_drain(axis);
    peak = std::max(peak, axis.velocity_turns_per_s());
  }
  EXPECT_NEAR(peak, 1.0, 0.05);
  EXPECT_NEAR(axis.position_turns(), 2.0, 2e-3);
  EXPECT_TRUE(odrive_sim_heartbeat(axis, 1).trajectory_done);
}

TEST(SimOdriveAxis, VelocityAndTorqueControl) {
  SimOdriveAxis axis(odrive_sim_config());
  axis.receive(od::encode_set_controller_modes(1, od::ControlMode::velocity, od::InputMode::passthrough));
  axis.receive(od::encode_set_limits(1, 5.0f, 20.0f));
  axis.receive(od::encode_set_axis_state(1, od::AxisState::closed_loop_control));
  axis.receive(od::encode_set_input_vel(1, 2.0f));
  odrive_sim_run(axis, 0.5);
  EXPECT_NEAR(axis.velocity_turns_per_s(), 2.0, 0.05);  // less the friction's share

  SimOdriveAxis torque(odrive_sim_config());
  torque.receive(od::encode_set_controller_modes(1, od::ControlMode::torque, od::InputMode::passthrough));
  torque.receive(od::encode_set_axis_state(1, od::AxisState::closed_loop_control));
  torque.receive(od::encode_set_input_torque(1, 0.1f));
  odrive_sim_run(torque, 0.01);
  EXPECT_NEAR(torque.motor().torque(), 0.1, 1e-6);
  EXPECT_GT(torque.velocity_turns_per_s(), 0.0);
}

TEST(SimOdriveAxis, IdleAxisCoasts) {
  SimOdriveAxis axis(odrive_sim_config());
  axis.receive(od::encode_set_axis_state(1, od::AxisState::closed_loop_control));
  axis.receive(od::encode_set_input_pos(1, 1.0f));
  odrive_sim_run(axis, 0.1);
  axis.receive(od::encode_set_axis_state(1, od::AxisState::idle));
  const double released_at = axis.velocity_turns_per_s();
  axis.receive(od::encode_set_input_pos(1, -1.0f));  // no torque while idle
  odrive_sim_run(axis, 1.0);
  EXPECT_EQ(axis.motor().torque(), 0.0);
  EXPECT_GT(axis.velocity_turns_per_s(), 0.0);
  EXPECT_LT(axis.velocity_turns_per_s(), 0.5 * released_at);  // friction slows it
}

}  // namespace
}  // namespace avar::sim
