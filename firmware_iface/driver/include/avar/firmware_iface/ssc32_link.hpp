#pragma once
// The Lynxmotion SSC-32 / SSC-32U driver over any ByteTransport: per tick ONE write of one group
// move line holding every driven channel, with T = the tick period so the board sweeps each
// servo smoothly to its new pulse in exactly one tick (and a line holding newly released
// channels low, ahead of it, when there are any). read_positions() asks QP for every channel.

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "avar/firmware_iface/actuator_link.hpp"
#include "avar/firmware_iface/actuator_table.hpp"
#include "avar/firmware_iface/byte_transport.hpp"
#include "avar/firmware_iface/linear_calibration.hpp"
#include "avar/firmware_iface/reconnector.hpp"
#include "avar/firmware_iface/ssc32_codec.hpp"

namespace avar::firmware_iface {

struct Ssc32Actuator {
  std::size_t channel = 0;               ///< rig channel index
  int device_channel = 0;                ///< SSC-32 channel, 0..31
  LinearCalibration calibration;         ///< channel units -> pulse width in µs (500..2500 on the board)
  std::optional<double> speed_us_per_s;  ///< the board's per-servo S limit, 1..65535
};

struct Ssc32LinkConfig {
  int baud = 115200;  ///< the rate the transport was opened at (9600 / 38400 / 115200); describe() only
  /// The loop's tick period: every group move carries T = this in ms (0: no T, servos jump).
  std::chrono::milliseconds move_time{20};
  std::chrono::milliseconds reply_timeout{50};  ///< for the Q and QP queries
  std::vector<Ssc32Actuator> actuators;
};

class Ssc32Link final : public ActuatorLink {
 public:
  /// Throws std::invalid_argument for no actuators, a device channel outside 0..31 or used twice.
  Ssc32Link(ByteTransport& transport, Ssc32LinkConfig config);

  /// Asks Q and waits for the one-byte answer: a board that does not answer is a timeout.
  Status start() override;
  /// QP for every actuator: the pulse each channel outputs (10 µs resolution) in channel units;
  /// a channel with no pulse yet stays unknown. Not real-time.
  Status read_positions(std::span<double> frame, std::span<bool> known) override;
  /// Real-time safe: one write.
  Status send(std::span<const double> frame) noexcept override;
  /// Holds every actuator's output low (no pulses). Real-time safe.
  Status release() noexcept override;
  void release_channel(std::size_t channel) noexcept override;
  std::uint64_t saturated_pulses() const noexcept override { return table_.saturated(); }
  const std::string& describe() const noexcept override { return description_; }
  /// Only reconnects: the device does not answer every tick.
  LinkCounters counters() const noexcept override { return reconnector_.counters(); }

  /// True while the board says a move is still running (Q). Not real-time.
  Status query_moving(bool& moving);
  std::size_t last_send_size() const noexcept { return last_send_size_; }

 private:
  ByteTransport& transport_;
  Ssc32LinkConfig config_;
  std::string description_;
  ActuatorTable table_;
  std::vector<ssc32::ServoMove> moves_;
  std::vector<std::uint8_t> channels_;
  std::vector<std::uint8_t> packet_;
  std::size_t last_send_size_ = 0;
  Reconnector reconnector_;  ///< reopens the port after an I/O error
};

}  // namespace avar::firmware_iface
