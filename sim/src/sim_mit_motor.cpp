#include "avar/sim/sim_mit_motor.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>

namespace avar::sim {
namespace mit = firmware_iface::mit;

SimMitMotor::SimMitMotor(SimMitMotorConfig config) : config_(config), model_(config_.motor, config_.initial_position) {
  if (config_.id > firmware_iface::kCanMaxStandardId || config_.master_id > firmware_iface::kCanMaxStandardId ||
      config_.id == config_.master_id)
    throw std::invalid_argument("simulated MIT motor " + std::to_string(config_.id) +
                                ": CAN_ID and CAN_MASTER must be two 11-bit IDs");
  if (!config_.ranges.valid())
    throw std::invalid_argument("simulated MIT motor " + std::to_string(config_.id) + ": invalid ranges");
  if (config_.reply_length < 6 || config_.reply_length > 8)
    throw std::invalid_argument("simulated MIT motor " + std::to_string(config_.id) + ": replies are 6 to 8 bytes");
}

void SimMitMotor::receive(const firmware_iface::CanFrame& frame) {
  if (frame.error || frame.rtr || frame.extended || frame.id != config_.id || frame.dlc != 8) return;
  ++frames_accepted_;
  const std::span<const std::uint8_t, 8> data(frame.data.data(), 8);
  switch (mit::classify(data)) {
    case mit::MitFrameKind::enter_motor_mode:
      // The firmware enters motor mode with its commands cleared: no torque until the first one.
      motor_mode_ = true;
      command_ = {};
      timed_out_ = false;
      since_command_s_ = 0;
      break;
    case mit::MitFrameKind::exit_motor_mode: motor_mode_ = false; break;
    case mit::MitFrameKind::set_zero:
      // The notes do not say whether zeroing works in motor mode; the simulator zeroes only in
      // menu mode, the safe reading (a new zero under a held command would make the rotor jump).
      if (!motor_mode_) zero_offset_ = model_.position();
      break;
    case mit::MitFrameKind::command:
      command_ = mit::command_value(mit::unpack_command(data), config_.ranges);
      timed_out_ = false;
      since_command_s_ = 0;
      break;
  }
  reply();
}

void SimMitMotor::reply() {
  if (!answering_) return;
  const double torque = driving() ? model_.torque() : 0.0;
  const std::array<std::uint8_t, 6> six =
      mit::pack_reply(static_cast<std::uint8_t>(config_.id & 0xFF), model_.measured_position() - zero_offset_, model_.velocity(),
                      torque, config_.ranges);
  std::array<std::uint8_t, 8> bytes{};
  std::copy(six.begin(), six.end(), bytes.begin());
  outbox_.push_back(firmware_iface::can_data_frame(config_.master_id, std::span(bytes.data(), config_.reply_length)));
  ++replies_sent_;
}

bool SimMitMotor::peek_transmit(firmware_iface::CanFrame* frame) const {
  if (outbox_.empty()) return false;
  *frame = outbox_.front();
  return true;
}

void SimMitMotor::pop_transmit() {
  if (!outbox_.empty()) outbox_.pop_front();
}

void SimMitMotor::advance(double dt_s) {
  if (dt_s <= 0) return;
  if (motor_mode_ && !timed_out_) {
    since_command_s_ += dt_s;
    if (config_.command_timeout_s > 0 && since_command_s_ > config_.command_timeout_s) timed_out_ = true;
  }
  MotorCommand c;
  c.enabled = driving();
  c.position = command_.position + zero_offset_;
  c.velocity = command_.velocity;
  c.kp = command_.kp;
  c.kd = command_.kd;
  c.torque_ff = command_.torque;
  model_.advance(dt_s, c);
}

}  // namespace avar::sim
