#pragma once
// What a simulated Pololu Maestro does with its channels, whichever way the commands come (the
// serial protocol: SimMaestro; native USB vendor requests: SimMaestroUsb): each channel's target
// clamped to its range, its output pulse moving toward the target under the speed and
// acceleration limits (the 20 ms-period units), one ServoModel following that pulse, and the
// error register, whose every error sends the channels home.
//
// Units: targets and output pulses in quarter-µs (0 = no pulses), configuration in µs, time in
// seconds. Not thread-safe: the device that owns it is served by one host at a time.

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "avar/sim/servo_model.hpp"

namespace avar::sim {

/// One channel's device settings ("Channel Settings" in the Maestro's configuration).
struct SimMaestroChannel {
  double min_us = 992;  ///< targets are clamped to [min_us, max_us]
  double max_us = 2000;
  double home_us = 0;                 ///< Go Home and errors go here; 0 = "Off" (stop pulses)
  bool home_ignore = false;           ///< home mode "Ignore": Go Home and errors leave the channel alone
  double neutral_us = 1500;           ///< Mini SSC target8 127
  double range_us = 476.25;           ///< Mini SSC target8 0 and 254 are neutral -/+ this
  double initial_position_us = 1500;  ///< where the servo horn is at power-up
};

struct SimMaestroConfig {
  int channel_count = 24;            ///< 6 (Micro: no Set Multiple Targets, no Set PWM), 12, 18 or 24
  std::uint8_t device_number = 12;   ///< 0..127, for the Pololu form
  std::uint8_t mini_ssc_offset = 0;  ///< Mini SSC address of channel 0, 0..254
  bool crc = false;                  ///< expect a CRC-7 byte after every command but Mini SSC
  bool baud_detect = false;          ///< "UART, detect baud rate": bytes before the first 0xAA are
                                     ///< line noise; that 0xAA may stand alone or begin a Pololu packet
  std::size_t log_limit = 0;         ///< keep up to this many decoded commands in log() (0 = none)
  ServoParams servo;
  std::array<SimMaestroChannel, 24> channels{};  ///< only the first channel_count are used
};

class MaestroServos {
 public:
  /// Throws std::invalid_argument ("simulated Maestro: ...") for a channel count other than
  /// 6/12/18/24, a device number above 127, a Mini SSC offset above 254, a used channel whose
  /// range is not 0 < min_us <= max_us <= 4095.75 or whose home is outside it (other than 0 =
  /// off), or servo parameters that are not positive (speed) or not non-negative (lag, deadband).
  explicit MaestroServos(const SimMaestroConfig& config);

  int channel_count() const { return static_cast<int>(channels_.size()); }
  /// Precondition for every channel argument: 0 <= channel < channel_count().
  /// Clamps to the channel's range; 0 stops the pulses. From "no pulses" the first pulse is
  /// the target itself.
  void set_target(int channel, std::uint16_t quarter_us);
  /// Speed in units of 25 µs/s (0 = unlimited); values above 10000 count as 10000.
  void set_speed(int channel, std::uint16_t speed);
  /// Acceleration in units of 312.5 µs/s² (0 = unlimited); values above 255 count as 255.
  void set_acceleration(int channel, std::uint16_t acceleration);
  /// Every channel but the "Ignore" ones goes to its home (0 = off).
  void go_home();
  /// Sets error bits and sends every channel home, as the device does on any error.
  void raise(std::uint16_t error_bits);
  std::uint16_t errors() const { return errors_; }
  void clear_errors() { errors_ = 0; }

  /// Moves every output pulse toward its target for dt_s seconds and lets each servo follow
  /// it (in sub-steps of at most 1 ms). dt_s <= 0 does nothing.
  void advance(double dt_s);

  std::uint16_t target(int channel) const { return channels_[static_cast<std::size_t>(channel)].target_q; }
  double output_pulse(int channel) const { return channels_[static_cast<std::size_t>(channel)].output_q; }
  double servo_position_us(int channel) const { return channels_[static_cast<std::size_t>(channel)].servo.position_us(); }
  std::uint16_t speed(int channel) const { return channels_[static_cast<std::size_t>(channel)].speed; }
  std::uint16_t acceleration(int channel) const { return channels_[static_cast<std::size_t>(channel)].acceleration; }
  /// True while some channel's output pulse has not reached its target.
  bool moving() const;
  const SimMaestroChannel& settings(int channel) const { return settings_[static_cast<std::size_t>(channel)]; }

 private:
  struct Channel {
    std::uint16_t target_q = 0;
    double output_q = 0;
    double velocity_q = 0;  ///< quarter-µs per second, signed; carried between steps for acceleration
    std::uint16_t speed = 0;
    std::uint16_t acceleration = 0;
    ServoModel servo;
  };
  static void move_output(Channel& c, double dt_s);

  std::array<SimMaestroChannel, 24> settings_;
  std::vector<Channel> channels_;
  std::uint16_t errors_ = 0;
};

}  // namespace avar::sim
