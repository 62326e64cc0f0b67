#pragma once
// A simulated Pololu Mini/Micro Maestro (../shared/protocols/pololu-maestro.md): decodes the
// compact, Pololu and Mini SSC forms byte by byte, with optional CRC-7, answers the queries
// with the exact reply bytes, keeps the error register, moves each channel's output pulse
// under its speed and acceleration limits, and drives a ServoModel per channel.
// Not thread-safe: a host (PtyDeviceHost) serialises calls.

#include <array>
#include <cstdint>
#include <deque>
#include <initializer_list>
#include <vector>

#include "avar/sim/byte_device.hpp"
#include "avar/sim/servo_model.hpp"

namespace avar::sim {

struct SimMaestroChannel {
  double min_us = 992;               ///< targets are clamped to [min_us, max_us] (device setting)
  double max_us = 2000;
  double home_us = 0;                ///< Go Home and errors: 0 = "off" (stop pulses)
  double initial_position_us = 1500; ///< where the servo horn is at power-up
};

struct SimMaestroConfig {
  int channel_count = 24;            ///< 6 (Micro: no Set Multiple Targets), 12, 18 or 24
  std::uint8_t device_number = 12;
  std::uint8_t mini_ssc_offset = 0;
  bool crc = false;                  ///< expect a CRC-7 byte after every command
  bool baud_detect = false;          ///< a lone leading 0xAA is the baud-detection byte
  std::size_t log_limit = 0;         ///< keep up to this many decoded commands for inspection
  ServoParams servo;
  std::array<SimMaestroChannel, 24> channels{};
};

/// One decoded command, as the device understood it.
struct MaestroCommand {
  std::uint8_t command = 0;          ///< compact command byte (0x84...), or 0xFF for Mini SSC
  std::uint8_t channel = 0;          ///< first channel it addresses (0 when none)
  std::vector<std::uint16_t> values; ///< targets (quarter-µs), speed, acceleration... as sent
};

class SimMaestro final : public ByteDevice {
 public:
  explicit SimMaestro(SimMaestroConfig config);

  void receive(std::span<const std::uint8_t> bytes) override;
  std::size_t take_replies(std::span<std::uint8_t> out) override;
  void advance(double dt_s) override;
  std::uint64_t bytes_received() const override { return bytes_received_; }

  /// Target and current output pulse of a channel in quarter-µs (0 = no pulses).
  std::uint16_t target(int channel) const { return channels_[channel].target_q; }
  double output_pulse(int channel) const { return channels_[channel].output_q; }
  /// Where the simulated servo horn is, in µs of pulse width.
  double servo_position_us(int channel) const { return channels_[channel].servo.position_us(); }
  std::uint16_t speed(int channel) const { return channels_[channel].speed; }
  std::uint16_t acceleration(int channel) const { return channels_[channel].acceleration; }
  /// The error register without clearing it (Get Errors clears it).
  std::uint16_t errors() const { return errors_; }
  const std::deque<MaestroCommand>& log() const { return log_; }
  const SimMaestroConfig& config() const { return config_; }

 private:
  struct Channel {
    std::uint16_t target_q = 0;
    double output_q = 0;
    double velocity_q = 0;  ///< quarter-µs per second, for acceleration limiting
    std::uint16_t speed = 0;
    std::uint16_t acceleration = 0;
    ServoModel servo;
  };
  enum class State { idle, pololu_device, pololu_command, payload, mini_ssc };

  void start_command(std::uint8_t command_byte);
  std::size_t payload_size() const;
  void finish_packet();
  void execute();
  void set_target(int channel, std::uint16_t quarter_us);
  void raise(std::uint16_t error_bits);
  void reply(std::initializer_list<std::uint8_t> bytes);
  std::uint16_t value14(std::size_t at) const;

  SimMaestroConfig config_;
  std::vector<Channel> channels_;
  std::uint16_t errors_ = 0;
  std::uint64_t bytes_received_ = 0;
  bool baud_locked_ = false;
  std::deque<std::uint8_t> replies_;
  std::deque<MaestroCommand> log_;

  // Parser state for the packet under way.
  State state_ = State::idle;
  std::vector<std::uint8_t> packet_;   ///< every byte of the packet so far (for the CRC)
  std::vector<std::uint8_t> payload_;  ///< data bytes after the command byte
  std::uint8_t command_ = 0;           ///< compact form of the command
  bool for_us_ = true;                 ///< false: a Pololu packet for another device number
};

}  // namespace avar::sim
