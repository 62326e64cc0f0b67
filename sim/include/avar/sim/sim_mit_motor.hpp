#pragma once
// A simulated MIT mini-cheetah style CAN motor (../shared/protocols/mit-cheetah-can.md): menu
// mode (no torque) and motor mode, entered and left by the special frames; commands decoded
// exactly as the firmware decodes them (so quantisation is real) and applied as the impedance
// law on a CanMotorModel; set zero; the command timeout; and one reply, to the master ID with its
// own ID in byte 0, for every frame it accepts. Frames of another length than 8 are ignored.
// Not thread-safe: its bus serialises every call.

#include <cstdint>
#include <deque>

#include "avar/firmware_iface/mit_can_codec.hpp"
#include "avar/sim/can_motor_model.hpp"
#include "avar/sim/can_node.hpp"

namespace avar::sim {

struct SimMitMotorConfig {
  std::uint32_t id = 1;         ///< CAN_ID: the standard ID it listens on (firmware default 1)
  std::uint32_t master_id = 0;  ///< CAN_MASTER: the standard ID it replies to (firmware default 0)
  firmware_iface::mit::MitRanges ranges = firmware_iface::mit::kMiniCheetahRanges;
  CanMotorParams motor{.inertia = 2e-3, .max_velocity = 40, .max_torque = 18};
  double initial_position = 0;  ///< rad, in the motor's own frame (after its zero)
  /// CAN_TIMEOUT: without a command for this long in motor mode, the motor applies no torque
  /// until the next command. The firmware's unit is unconfirmed (notes §2), so it is set here in
  /// seconds; 0 turns it off.
  double command_timeout_s = 0.1;
  /// 6 as the firmware; 8 for a clone that appends two bytes (temperature, error code: zero here).
  std::uint8_t reply_length = 6;
};

class SimMitMotor final : public CanNode {
 public:
  explicit SimMitMotor(SimMitMotorConfig config);

  void receive(const firmware_iface::CanFrame& frame) override;
  bool peek_transmit(firmware_iface::CanFrame* frame) const override;
  void pop_transmit() override;
  void advance(double dt_s) override;

  bool motor_mode() const { return motor_mode_; }
  /// Motor mode and a command not yet timed out: the impedance law is applied.
  bool driving() const { return motor_mode_ && !timed_out_; }
  /// The last command as the motor decoded it (what quantisation left of it).
  const firmware_iface::mit::MitCommand& command() const { return command_; }
  /// Ground truth: the rotor's position in the motor's own frame (after set zero), rad.
  double position() const { return model_.position() - zero_offset_; }
  double velocity() const { return model_.velocity(); }  ///< rad/s
  double torque() const { return model_.torque(); }      ///< N·m, last applied
  CanMotorModel& model() { return model_; }              ///< for loads leaning on the arm

  /// Frames it accepted (answered or not) and replies it queued, since construction.
  std::uint64_t frames_accepted() const { return frames_accepted_; }
  std::uint64_t replies_sent() const { return replies_sent_; }

  /// Fault injection: a motor that stops answering (a broken transmitter, a firmware hang of its
  /// CAN task) still hears and obeys commands but sends nothing.
  void set_answering(bool on) { answering_ = on; }

 private:
  void reply();

  SimMitMotorConfig config_;
  CanMotorModel model_;
  double zero_offset_ = 0;  // model position at the motor's zero, rad
  bool motor_mode_ = false;
  bool timed_out_ = false;
  double since_command_s_ = 0;
  firmware_iface::mit::MitCommand command_;
  bool answering_ = true;
  std::deque<firmware_iface::CanFrame> outbox_;
  std::uint64_t frames_accepted_ = 0;
  std::uint64_t replies_sent_ = 0;
};

}  // namespace avar::sim
