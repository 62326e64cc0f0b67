#include "avar/sim/sim_odrive_axis.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace avar::sim {
namespace {

namespace od = firmware_iface::odrive;
using firmware_iface::CanFrame;

constexpr double kRadPerTurn = 2 * std::numbers::pi;
constexpr std::size_t kTxQueueLimit = 32;  // frames waiting to win arbitration; more are dropped
constexpr double kTimerSlack_s = 1e-9;     // periods summed from 1 ms steps must still fire on time

constexpr std::uint8_t state_value(od::AxisState s) { return static_cast<std::uint8_t>(s); }
constexpr std::int32_t mode_value(od::ControlMode m) { return static_cast<std::int32_t>(m); }
constexpr std::int32_t mode_value(od::InputMode m) { return static_cast<std::int32_t>(m); }

bool all_finite(std::initializer_list<double> values) {
  return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

}  // namespace

SimOdriveAxis::SimOdriveAxis(SimOdriveAxisConfig config)
    : config_(config),
      motor_(config.motor, config.initial_position_turns * kRadPerTurn),
      velocity_limit_(config.velocity_limit),
      current_limit_(config.current_limit) {}

double SimOdriveAxis::position_turns() const noexcept { return motor_.position() / kRadPerTurn; }
double SimOdriveAxis::velocity_turns_per_s() const noexcept { return motor_.velocity() / kRadPerTurn; }

void SimOdriveAxis::set_position_turns(double turns) noexcept { motor_.set_position(turns * kRadPerTurn); }

void SimOdriveAxis::inject_axis_error(std::uint32_t bits, std::uint64_t motor_error) {
  axis_error_ |= bits;
  motor_error_ |= motor_error;
  enter_idle();
}

void SimOdriveAxis::receive(const CanFrame& f) {
  if (f.error || f.extended || f.id > firmware_iface::kCanMaxStandardId || od::odrive_node(f.id) != config_.node) return;
  bool used = true;
  if (od::is_command(f, od::kEstop)) {
    inject_axis_error(od::kEstopRequested);
  } else if (od::is_command(f, od::kClearErrors)) {
    axis_error_ = 0;
    motor_error_ = 0;
  } else if (std::uint32_t state = 0; od::decode_set_axis_state(f, &state)) {
    request_state(state);
  } else if (od::ControllerModes m; od::decode_set_controller_modes(f, &m)) {
    const bool known = m.control_mode >= mode_value(od::ControlMode::voltage) &&
                       m.control_mode <= mode_value(od::ControlMode::position) &&
                       m.input_mode >= mode_value(od::InputMode::inactive) && m.input_mode <= mode_value(od::InputMode::mirror);
    if (known) {
      control_mode_ = m.control_mode;
      input_mode_ = m.input_mode;
    }
    used = known;
  } else if (od::InputPos p; od::decode_set_input_pos(f, &p)) {
    used = all_finite({p.position});
    if (used) {
      input_pos_ = p.position;
      input_vel_ = p.vel_ff;
      input_torque_ = p.torque_ff;
      if (input_mode_ == mode_value(od::InputMode::trap_traj)) trajectory_done_ = false;
    }
  } else if (float vel = 0, torque_ff = 0; od::decode_set_input_vel(f, &vel, &torque_ff)) {
    used = all_finite({vel, torque_ff});
    if (used) input_vel_ = vel, input_torque_ = torque_ff;
  } else if (float torque = 0; od::decode_set_input_torque(f, &torque)) {
    used = all_finite({torque});
    if (used) input_torque_ = torque;
  } else if (od::Limits l; od::decode_set_limits(f, &l)) {
    used = all_finite({l.velocity_limit, l.current_limit}) && l.velocity_limit > 0 && l.current_limit > 0;
    if (used) velocity_limit_ = l.velocity_limit, current_limit_ = l.current_limit;
  } else if (od::is_request(f, od::kGetEncoderEstimates)) {
    used = answers_requests_;
    if (used) send_encoder_estimates();
  } else if (od::is_request(f, od::kGetMotorError)) {
    used = answers_requests_;
    if (used) queue(od::encode_motor_error(config_.node, motor_error_));
  } else {
    used = false;
  }
  if (used) ++frames_received_;
}

void SimOdriveAxis::request_state(std::uint32_t state) {
  if (state == state_value(od::AxisState::idle)) {
    enter_idle();
  } else if (state == state_value(od::AxisState::closed_loop_control)) {
    if (axis_error_ != 0) {
      enter_idle();  // the firmware's checks fail on the latched error; nothing new is latched
    } else if (!config_.calibrated) {
      inject_axis_error(od::kInvalidState);
    } else if (state_ != state_value(od::AxisState::closed_loop_control) && !entering_closed_loop_) {
      entering_closed_loop_ = true;
      entry_elapsed_s_ = 0;
      if (config_.closed_loop_entry_s <= 0) enter_closed_loop();
    }
  } else {
    // No calibration, homing or sensorless sequence is simulated.
    inject_axis_error(od::kInvalidState);
  }
}

void SimOdriveAxis::enter_idle() noexcept {
  state_ = state_value(od::AxisState::idle);
  entering_closed_loop_ = false;
}

void SimOdriveAxis::enter_closed_loop() noexcept {
  entering_closed_loop_ = false;
  state_ = state_value(od::AxisState::closed_loop_control);
  const double present = position_turns();
  if (config_.hold_position_on_entry) {
    input_pos_ = present;
    input_vel_ = 0;
    input_torque_ = 0;
  }
  pos_setpoint_ = present;
  vel_setpoint_ = 0;
  torque_setpoint_ = 0;
  trajectory_done_ = true;
}

void SimOdriveAxis::queue(const CanFrame& frame) {
  if (tx_.size() < kTxQueueLimit) tx_.push_back(frame);
}

bool SimOdriveAxis::peek_transmit(CanFrame* frame) const {
  if (tx_.empty()) return false;
  *frame = tx_.front();
  return true;
}

void SimOdriveAxis::pop_transmit() {
  if (!tx_.empty()) tx_.pop_front();
}

void SimOdriveAxis::send_heartbeat() {
  od::Heartbeat h;
  h.axis_error = axis_error_;
  h.state = state_;
  h.motor_error = motor_error_ != 0;
  // Only a trapezoidal move is a trajectory (idle and closed-loop heartbeats match O1 and O2).
  h.trajectory_done = trajectory_done_ && input_mode_ == mode_value(od::InputMode::trap_traj);
  queue(od::encode_heartbeat(config_.node, h, config_.heartbeat_layout));
  ++heartbeats_sent_;
}

void SimOdriveAxis::send_encoder_estimates() {
  queue(od::encode_encoder_estimates(config_.node, static_cast<float>(motor_.measured_position() / kRadPerTurn),
                                     static_cast<float>(velocity_turns_per_s())));
}

void SimOdriveAxis::update_setpoints(double h) noexcept {
  if (control_mode_ == mode_value(od::ControlMode::torque)) {
    torque_setpoint_ = input_torque_;
    return;
  }
  if (control_mode_ == mode_value(od::ControlMode::velocity)) {
    vel_setpoint_ = input_vel_;
    torque_setpoint_ = input_torque_;
    return;
  }
  if (input_mode_ == mode_value(od::InputMode::pos_filter)) {
    // The firmware's critically damped 2nd-order filter: kp = bw², ki = 2·bw.
    const double bw = config_.input_filter_bandwidth;
    const double accel = bw * bw * (input_pos_ - pos_setpoint_) + 2 * bw * (input_vel_ - vel_setpoint_);
    vel_setpoint_ += h * accel;
    pos_setpoint_ += h * vel_setpoint_;
    torque_setpoint_ = input_torque_;
  } else if (input_mode_ == mode_value(od::InputMode::trap_traj)) {
    // Tracked online rather than planned once: accelerate at the accel limit toward the cruise
    // velocity, brake at the decel limit so as to stop on the goal.
    const double distance = input_pos_ - pos_setpoint_;
    const double decel = config_.trap_decel_limit, accel = config_.trap_accel_limit;
    if (std::abs(distance) <= 1e-6 && std::abs(vel_setpoint_) <= decel * h) {
      pos_setpoint_ = input_pos_;
      vel_setpoint_ = 0;
      trajectory_done_ = true;
    } else {
      const double target = std::copysign(std::min(config_.trap_vel_limit, std::sqrt(2 * decel * std::abs(distance))), distance);
      const bool braking = target * vel_setpoint_ >= 0 && std::abs(target) < std::abs(vel_setpoint_);
      const double step = (braking ? decel : accel) * h;
      vel_setpoint_ += std::clamp(target - vel_setpoint_, -step, step);
      const double next = pos_setpoint_ + h * vel_setpoint_;
      // Never step past the goal: arrive and stop.
      if ((input_pos_ - next) * distance <= 0) {
        pos_setpoint_ = input_pos_;
        vel_setpoint_ = 0;
        trajectory_done_ = true;
      } else {
        pos_setpoint_ = next;
      }
    }
    torque_setpoint_ = 0;
  } else {
    pos_setpoint_ = input_pos_;
    vel_setpoint_ = input_vel_;
    torque_setpoint_ = input_torque_;
  }
}

double SimOdriveAxis::control_step(double h) noexcept {
  update_setpoints(h);
  double torque = torque_setpoint_;
  if (control_mode_ != mode_value(od::ControlMode::torque)) {
    double vel_des = vel_setpoint_;
    if (control_mode_ == mode_value(od::ControlMode::position)) vel_des += config_.pos_gain * (pos_setpoint_ - position_turns());
    vel_des = std::clamp(vel_des, -velocity_limit_, velocity_limit_);
    torque += config_.vel_gain * (vel_des - velocity_turns_per_s());
  }
  const double max_torque = current_limit_ * config_.torque_constant;
  return std::clamp(torque, -max_torque, max_torque);
}

void SimOdriveAxis::advance(double dt_s) {
  if (dt_s <= 0) return;
  if (entering_closed_loop_) {
    entry_elapsed_s_ += dt_s;
    if (entry_elapsed_s_ + kTimerSlack_s >= config_.closed_loop_entry_s) enter_closed_loop();
  }
  // The firmware's current loop runs at 8 kHz; the torque is held over each model step.
  for (double left = dt_s; left > 0;) {
    const double h = std::min(left, CanMotorModel::kMaxStep_s);
    left -= h;
    MotorCommand command;
    if (state_ == state_value(od::AxisState::closed_loop_control)) {
      command.enabled = true;
      command.torque_ff = control_step(h);
    }
    motor_.advance(h, command);
  }
  if (config_.heartbeat_period_s > 0) {
    heartbeat_elapsed_s_ += dt_s;
    while (heartbeat_elapsed_s_ + kTimerSlack_s >= config_.heartbeat_period_s) {
      heartbeat_elapsed_s_ -= config_.heartbeat_period_s;
      if (heartbeat_enabled_) send_heartbeat();
    }
  }
  if (config_.encoder_period_s > 0) {
    encoder_elapsed_s_ += dt_s;
    while (encoder_elapsed_s_ + kTimerSlack_s >= config_.encoder_period_s) {
      encoder_elapsed_s_ -= config_.encoder_period_s;
      send_encoder_estimates();
    }
  }
}

}  // namespace avar::sim
