#pragma once
// A simulated Lynxmotion SSC-32U (../shared/protocols/ssc32.md): buffers characters until CR
// (ESC drops the line), runs each line through the board's parser (firmware_iface::ssc32) and
// does what the board does: group moves whose servos all start and arrive together (the group
// takes the longer of its T and each servo's distance / S), pulse offsets, outputs held low or
// high (no pulses), and the QP / Q queries answered with raw bytes.
//
// Behaviour the notes leave open, as modelled here:
//  - A channel's first move after power-up (or after being an output) jumps: there is no start
//    pulse to sweep from.
//  - QP reports the commanded pulse without its offset; the servo sees the pulse plus offset.
//  - Invalid lines (see ssc32::parse_line) and lines longer than kMaxLine are ignored.
// Units: pulses in µs, time in seconds. Not thread-safe: a host serialises every call.

#include <array>
#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "avar/firmware_iface/ssc32_codec.hpp"
#include "avar/sim/byte_device.hpp"
#include "avar/sim/servo_model.hpp"

namespace avar::sim {

struct SimSsc32Config {
  int baud = 115200;  ///< 9600, 38400 or 115200 (the button's choices); for wire_time()
  ServoParams servo;
  double initial_position_us = 1500;  ///< where every servo horn is at power-up
  std::size_t log_limit = 0;          ///< keep up to this many accepted lines in log()
};

class SimSsc32 final : public ByteDevice {
 public:
  static constexpr std::size_t kMaxLine = 512;

  /// Throws std::invalid_argument for a baud rate the board cannot be set to.
  explicit SimSsc32(SimSsc32Config config);

  void receive(std::span<const std::uint8_t> bytes) override;
  std::size_t take_replies(std::span<std::uint8_t> out) override;
  /// Moves every output along its group move and lets each servo follow (sub-steps <= 1 ms).
  void advance(double dt_s) override;
  std::uint64_t bytes_received() const override { return bytes_received_; }

  /// Pulse the channel outputs now, µs (0 = none).
  double output_pulse(int channel) const { return channels_[channel].output; }
  /// Where the channel's move ends, µs (0 = none).
  double target(int channel) const { return channels_[channel].target; }
  double servo_position_us(int channel) const { return channels_[channel].servo.position_us(); }
  int offset(int channel) const { return channels_[channel].offset; }
  /// True while some channel's move has not ended (what Q answers).
  bool moving() const;
  /// Seconds `bytes` take on the line at its baud rate (8N1).
  double wire_time(std::size_t bytes) const;
  /// Typical delay before a query reply starts (the manual: within 100 µs).
  static constexpr double kReplyDelay_s = 100e-6;
  const std::deque<std::string>& log() const { return log_; }

 private:
  struct Channel {
    double output = 0;  ///< µs, 0 = no pulses
    double start = 0;
    double target = 0;
    double elapsed = 0;
    double duration = 0;
    int offset = 0;
    ServoModel servo;
  };
  void execute();
  void move(const firmware_iface::ssc32::Command& c);

  SimSsc32Config config_;
  std::array<Channel, firmware_iface::ssc32::kChannels> channels_{};
  std::vector<std::uint8_t> line_;
  bool overflow_ = false;
  std::deque<std::uint8_t> replies_;
  std::deque<std::string> log_;
  std::uint64_t bytes_received_ = 0;
};

}  // namespace avar::sim
