#pragma once
// A simulated ENTTEC DMX USB Pro widget (../shared/protocols/enttec-dmx-usb-pro.md) with DMX
// servo decoders on its line. It decodes the widget's messages (resynchronising past anything
// that is not one), keeps the universe of the last Output Only Send DMX message, answers Get
// Widget Parameters and Get Serial Number, takes Set Widget Parameters, and counts the DMX
// packets it puts on the line at its output rate. Each configured fixture turns its slot (or
// coarse/fine slot pair) into a servo pulse that a ServoModel follows.
//
// Behaviour the notes leave open, as modelled here: label 6 gives no reply; a label 6 message
// with fewer than 24 slots or more than 512, or a Set Widget Parameters with values out of
// range, is ignored; the widget re-sends the last universe until new data comes.
// Units: pulses in µs, time in seconds. Not thread-safe: a host serialises every call.

#include <array>
#include <cstdint>
#include <vector>
#include <deque>

#include "avar/firmware_iface/dmx_codec.hpp"
#include "avar/sim/byte_device.hpp"
#include "avar/sim/servo_model.hpp"

namespace avar::sim {

/// A DMX servo decoder: level 0 -> pulse_at_zero, full level -> pulse_at_full.
struct SimDmxFixture {
  int address = 1;    ///< first slot, 1..512
  bool fine = false;  ///< 16-bit: address = coarse, address + 1 = fine
  double pulse_at_zero_us = 1000;
  double pulse_at_full_us = 2000;
  double initial_position_us = 1500;
};

struct SimDmxConfig {
  /// Host-side serial rate the link budget assumes (8N1). The real widget's USB link ignores
  /// the rate a host sets (unconfirmed); the DMX line itself runs at 250 kbit/s 8N2.
  int baud = 115200;
  std::vector<SimDmxFixture> fixtures;
  ServoParams servo;
  firmware_iface::dmx::WidgetParameters parameters{0x0144, 9, 1, 40};
  std::uint32_t serial_number = 0x12345678;  ///< answered as 4 bytes, least significant first
};

class SimDmx final : public ByteDevice {
 public:
  /// Throws std::invalid_argument for a fixture whose slots are outside 1..512.
  explicit SimDmx(SimDmxConfig config);

  void receive(std::span<const std::uint8_t> bytes) override;
  std::size_t take_replies(std::span<std::uint8_t> out) override;
  /// Puts DMX packets on the line at the output rate and moves the fixtures' servos.
  void advance(double dt_s) override;
  std::uint64_t bytes_received() const override { return bytes_received_; }

  /// Slot value, 1-based DMX address; 0 for slots never sent.
  std::uint8_t slot(int address) const { return universe_[static_cast<std::size_t>(address - 1)]; }
  std::size_t slot_count() const { return slot_count_; }
  std::uint8_t start_code() const { return start_code_; }
  std::uint64_t frames_received() const { return frames_; }
  std::uint64_t framing_errors() const { return framing_errors_; }
  /// DMX packets transmitted on the line since start.
  std::uint64_t dmx_packets_sent() const { return dmx_packets_; }
  const firmware_iface::dmx::WidgetParameters& parameters() const { return config_.parameters; }
  /// The level a fixture reads now (0..255, or 0..65535 for a fine one).
  int fixture_level(std::size_t fixture) const;
  double fixture_pulse_us(std::size_t fixture) const;
  double servo_position_us(std::size_t fixture) const { return servos_[fixture].position_us(); }
  /// Seconds `bytes` take on the host side at the configured rate (8N1).
  double wire_time(std::size_t bytes) const;
  /// Seconds between DMX packets: the output rate's period, never shorter than the packet.
  double dmx_period() const;

 private:
  void handle(std::uint8_t label, std::span<const std::uint8_t> data);

  SimDmxConfig config_;
  std::array<std::uint8_t, firmware_iface::dmx::kUniverseSize> universe_{};
  std::size_t slot_count_ = 0;
  std::uint8_t start_code_ = 0;
  std::vector<ServoModel> servos_;
  std::vector<std::uint8_t> input_;
  std::deque<std::uint8_t> replies_;
  std::uint64_t bytes_received_ = 0;
  std::uint64_t frames_ = 0;
  std::uint64_t framing_errors_ = 0;
  std::uint64_t dmx_packets_ = 0;
  double since_packet_ = 0;
};

}  // namespace avar::sim
