#pragma once
// A simulated Pololu Micro/Mini Maestro (shared/protocols/pololu-maestro.md). It decodes, byte by
// byte, exactly what the device accepts: the compact, Pololu and Mini SSC forms mixed freely,
// with the optional CRC-7 byte; it answers the queries with the exact reply bytes, keeps the
// error register, moves each channel's output pulse under its speed and acceleration limits
// (the 20 ms-period units), and drives one ServoModel per channel from that output pulse.
//
// Behaviour the protocol notes leave open, as modelled here:
//  - A Pololu packet for another device number is skipped unread: neither its CRC nor its
//    command is checked, and a command byte cutting it short is no error.
//  - Targets are clamped to the channel's [min_us, max_us]; a target for a channel the device
//    does not have is ignored, and Get Position of such a channel answers 0.
//  - Speed values above 10000 count as 10000, accelerations above 255 as 255.
//  - The output pulse moves continuously in simulated time (not in 10 ms jumps): without an
//    acceleration limit at the speed limit, with one along a trapezoid (speed up at the limit,
//    cruise at the speed limit, slow down to stop on the target).
//  - Any error sets its bit and sends every channel to its home position, as the device does.
//
// Units: targets and output pulses in quarter-µs (0 = no pulses), configuration in µs, time in
// seconds. Not thread-safe: a host (PtyDeviceHost) serialises every call.

#include <cstdint>
#include <deque>
#include <vector>

#include "avar/core/byte_order.hpp"
#include "avar/sim/byte_device.hpp"
#include "avar/sim/maestro_servos.hpp"

namespace avar::sim {

/// One decoded command, as the device understood it.
struct MaestroCommand {
  enum class Form : std::uint8_t { compact, pololu, mini_ssc };
  std::uint8_t command = 0;           ///< compact command byte (0x84...), 0xFF for Mini SSC
  std::uint8_t channel = 0;           ///< the (first) channel it addresses; 0 when none
  std::vector<std::uint16_t> values;  ///< as sent: targets (quarter-µs), speed, acceleration,
                                      ///< Set PWM on-time and period, subroutine (and parameter),
                                      ///< Mini SSC target8
  Form form = Form::compact;
};

class SimMaestro final : public ByteDevice {
 public:
  /// Throws std::invalid_argument for a channel count other than 6/12/18/24, a device number
  /// above 127, a Mini SSC offset above 254, a used channel whose range is not
  /// 0 < min_us <= max_us <= 4095.75 or whose home is outside it (other than 0 = off), or servo
  /// parameters that are not positive (speed) or not non-negative (lag, deadband).
  explicit SimMaestro(SimMaestroConfig config);

  /// Parses bytes in order; replies go to the outbox. Not for a real-time thread: the reply
  /// queue and the log allocate.
  void receive(std::span<const std::uint8_t> bytes) override;
  /// Moves up to out.size() pending reply bytes into out, oldest first; returns how many.
  std::size_t take_replies(std::span<std::uint8_t> out) override;
  /// Moves every output pulse toward its target for dt_s seconds and lets each servo follow it
  /// (in sub-steps of at most 1 ms). dt_s <= 0 does nothing.
  void advance(double dt_s) override;
  std::uint64_t bytes_received() const override { return bytes_received_; }

  // Inspection. Precondition: 0 <= channel < channel_count.
  /// Target in quarter-µs after clamping (0 = no pulses).
  std::uint16_t target(int channel) const { return servos_.target(channel); }
  /// Pulse being output now, quarter-µs (0 = none); Get Position answers it rounded.
  double output_pulse(int channel) const { return servos_.output_pulse(channel); }
  /// Where the simulated servo horn is, µs of pulse width.
  double servo_position_us(int channel) const { return servos_.servo_position_us(channel); }
  /// Speed limit in device units of 25 µs/s (0 = unlimited).
  std::uint16_t speed(int channel) const { return servos_.speed(channel); }
  /// Acceleration limit in device units of 312.5 µs/s² (0 = unlimited).
  std::uint16_t acceleration(int channel) const { return servos_.acceleration(channel); }
  /// True while some channel's output pulse has not reached its target (Get Moving State).
  bool moving() const { return servos_.moving(); }
  /// The error register without clearing it (Get Errors clears it).
  std::uint16_t errors() const { return servos_.errors(); }
  /// Reply bytes not yet taken.
  std::size_t pending_replies() const { return replies_.size(); }
  /// The last log_limit decoded commands, oldest first.
  const std::deque<MaestroCommand>& log() const { return log_; }
  const SimMaestroConfig& config() const { return config_; }

 private:
  enum class State { idle, skip, pololu_device, pololu_command, payload, mini_ssc };

  void take(std::uint8_t b);
  void begin_packet(std::uint8_t first_byte);
  void start_command(std::uint8_t command_byte);
  std::size_t payload_size() const;
  void take_payload(std::uint8_t b);
  void take_mini_ssc(std::uint8_t b);
  void finish_packet();
  void execute();
  void record(MaestroCommand command);
  void raise(std::uint16_t error_bits) { servos_.raise(error_bits); }
  void reply(std::uint8_t byte) { replies_.push_back(byte); }
  /// A two-byte reply, least significant byte first (positions, the error register).
  void reply_u16(std::uint16_t v) {
    std::uint8_t le[2];
    put_u16_le(le, v);
    replies_.insert(replies_.end(), le, le + 2);
  }
  std::uint16_t value14(std::size_t at) const;

  SimMaestroConfig config_;
  MaestroServos servos_;
  std::uint64_t bytes_received_ = 0;
  bool baud_locked_ = false;
  std::deque<std::uint8_t> replies_;
  std::deque<MaestroCommand> log_;

  // The packet under way.
  State state_ = State::idle;
  MaestroCommand::Form form_ = MaestroCommand::Form::compact;
  bool lone_baud_byte_ = false;        ///< the packet so far is the baud-detection 0xAA
  std::vector<std::uint8_t> packet_;   ///< every byte of the packet so far (for the CRC)
  std::vector<std::uint8_t> payload_;  ///< data bytes after the command byte
  std::uint8_t command_ = 0;           ///< compact form of the command
};

}  // namespace avar::sim
