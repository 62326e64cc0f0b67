#pragma once
// A simulated avar-device (docs/protocols/avar-device.md): the device's own streaming
// player (avar/device/stream_player.hpp, the source a board runs) built for the host, ticking at
// the device's control rate on simulated time, each channel's output a hobby-servo pulse (a
// straight line from its pulse at output 0 to its pulse at output 65535) that a servo model
// follows. Answers as the device does. Units: pulses in µs, time in seconds. Not thread-safe: a
// host serialises every call.

#include <array>
#include <cstdint>
#include <deque>
#include <vector>

#include "avar/device/limiter.hpp"
#include "avar/device/stream_player.hpp"
#include "avar/sim/byte_device.hpp"
#include "avar/sim/servo_model.hpp"

namespace avar::sim {

struct SimAvarDeviceChannel {
  device::ChannelLimits limits;    ///< at the device's rate (limiter_prepare'd), Q16 output units
  double pulse_at_low_us = 1000;   ///< the pulse at output 0
  double pulse_at_high_us = 2000;  ///< the pulse at output 65535
};

struct SimAvarDeviceConfig {
  int baud = 115200;
  std::uint16_t rate_hz = 200;       ///< the device's control ticks per second
  std::uint8_t knot_capacity = 16;   ///< knot frames it holds
  std::uint32_t watchdog_ms = 500;   ///< link silence that eases to rest
  std::uint32_t clock_start_us = 0;  ///< the device's microsecond counter at power-up (it wraps)
  std::vector<SimAvarDeviceChannel> channels;
  ServoParams servo;
};

class SimAvarDevice final : public ByteDevice {
 public:
  /// Throws std::invalid_argument for no channels, more than the protocol carries, limits the
  /// limiter cannot use, a rate of 0 or a capacity below 2.
  explicit SimAvarDevice(SimAvarDeviceConfig config);
  SimAvarDevice(const SimAvarDevice&) = delete;
  SimAvarDevice& operator=(const SimAvarDevice&) = delete;

  void receive(std::span<const std::uint8_t> bytes) override;
  std::size_t take_replies(std::span<std::uint8_t> out) override;
  /// Runs the player's control ticks that fall due and lets each servo follow its pulse.
  void advance(double dt_s) override;
  std::uint64_t bytes_received() const override { return bytes_received_; }

  std::size_t channel_count() const { return channels_.size(); }
  /// Channel c's 16-bit output (its limiter's position).
  std::uint16_t output(std::size_t c) const { return channels_[c].output; }
  /// The pulse channel c sends now, µs; 0 while released (no pulses).
  double pulse_us(std::size_t c) const;
  /// Where channel c's servo horn is, µs of pulse.
  double servo_position_us(std::size_t c) const { return servos_[c].position_us(); }
  const device::StreamPlayer& player() const { return player_; }
  /// The board's own fault (its servo board stopped answering): every output off, state kFault,
  /// until the device is made again.
  void fail() { device::stream_fault(player_); }
  /// Control ticks run since power-up.
  std::uint64_t ticks() const { return ticks_; }

 private:
  std::uint32_t now_us() const;

  SimAvarDeviceConfig config_;
  std::vector<std::array<std::uint8_t, device::kLimitsSize>> stored_;
  std::vector<device::StreamChannel> channels_;
  std::vector<std::uint32_t> times_;
  std::vector<firmware_iface::avar_device::Knot> knots_;
  std::vector<std::uint8_t> frame_;  ///< the player's parser's
  device::StreamPlayer player_{};
  std::vector<ServoModel> servos_;
  std::deque<std::uint8_t> replies_;
  double now_s_ = 0;
  double next_tick_s_ = 0;
  std::uint64_t ticks_ = 0;
  std::uint64_t bytes_received_ = 0;
};

}  // namespace avar::sim
