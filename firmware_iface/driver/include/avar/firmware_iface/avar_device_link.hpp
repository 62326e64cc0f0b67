#pragma once
// The avar-device streaming link over any ByteTransport (docs/protocols/avar-device.md):
// instead of a position every tick, a knot every few ticks (each channel's value and slope at a
// tick, sent `lead` ahead of that tick's time; sooner where the motion turns faster than the
// cubic between knots follows) and avar's clock; the device plays the cubic between knots at its
// own control rate through its own limiter, so a 115200-baud link carries a smooth motion at a
// fraction of its capacity. A knot's slope is the commanded motion's central difference, so a
// knot leaves one tick after its tick (two, when it comes sooner). Values travel as 16-bit output units over
// the channel's range (the calibration maps channel units to 0..65535); the device maps them to
// its outputs (pulses) itself.
//
// Time: the stream clock is avar's tick clock: tick k (the k-th send since start()) is at k tick
// periods, in µs wrapping at 2^32, and every knot is followed by it as kTime (plus the write's
// time on the wire at the link's baud rate: when the device has it); the device's clock follows
// it, so the device plays tick k's motion `lead` after tick k was sent, as steady as the loop's
// ticks and independent of the transport's own clock.

#include <array>
#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "avar/firmware_iface/actuator_link.hpp"
#include "avar/firmware_iface/actuator_table.hpp"
#include "avar/firmware_iface/avar_device_codec.hpp"
#include "avar/firmware_iface/byte_transport.hpp"
#include "avar/firmware_iface/linear_calibration.hpp"
#include "avar/firmware_iface/reconnector.hpp"

namespace avar::firmware_iface {

struct AvarDeviceActuator {
  std::size_t channel = 0;        ///< rig channel index
  int device_channel = 0;         ///< the device's channel: 0..n-1, each once
  LinearCalibration calibration;  ///< channel units -> output units (0 at the channel's min, 65535 at its max)
};

struct AvarDeviceLinkConfig {
  int baud = 115200;                      ///< the line's rate: describe(), and the clock's time on the wire
  std::chrono::microseconds tick{10000};  ///< the loop's tick period
  int knot_every = 5;                     ///< ticks per knot at the most, >= 1
  /// A knot comes sooner where the device's cubic would leave the commanded motion by more than
  /// this (output units of 65535), as close as every tick the device's room allows.
  double fit_tolerance = 16;
  std::chrono::microseconds lead{150000};  ///< how far ahead of its time a knot is sent
  std::chrono::milliseconds reply_timeout{100};
  std::vector<AvarDeviceActuator> actuators;
};

class AvarDeviceLink final : public ActuatorLink {
 public:
  /// Throws std::invalid_argument for no actuators, more than the protocol carries, device
  /// channels that are not 0..n-1 each once, a tick or knot spacing below 1, or a lead shorter
  /// than two knots (a knot must reach the device before its time comes).
  AvarDeviceLink(ByteTransport& transport, AvarDeviceLinkConfig config);
  AvarDeviceLink(const AvarDeviceLink&) = delete;  // its parser points into its own buffer
  AvarDeviceLink& operator=(const AvarDeviceLink&) = delete;

  /// Hello: the device must answer with its status, speak this protocol's version, drive as many
  /// channels as the link and hold the knots the lead needs (start_problem() says which failed).
  Status start() override;
  std::string start_problem() const override { return problem_; }
  /// Asks the device's outputs (its limiter's positions), in channel units. Not real-time.
  Status read_positions(std::span<double> frame, std::span<bool> known) override;
  /// Real-time safe: at most one write (a knot and the clock at most every knot_every ticks, sooner
  /// where the motion needs it; newly released channels at once).
  Status send(std::span<const double> frame) noexcept override;
  /// Every output off. Real-time safe.
  Status release() noexcept override;
  void release_channel(std::size_t channel) noexcept override;
  std::uint64_t saturated_pulses() const noexcept override { return table_.saturated(); }
  const std::string& describe() const noexcept override { return description_; }
  LinkCounters counters() const noexcept override { return reconnector_.counters(); }
  /// The lead: the device plays each tick's command this long after it was sent.
  double command_delay_s() const noexcept override { return static_cast<double>(config_.lead.count()) / 1e6; }

  /// What the device said at start().
  const avar_device::Status& device_status() const noexcept { return status_; }
  std::size_t last_send_size() const noexcept { return last_send_size_; }

 private:
  /// Reads frames until one of `type` arrives (its payload in parser_) or the reply timeout.
  Status await(std::uint8_t type);
  /// Tick `tick`'s commanded value of device channel d, and its slope (output units per second).
  double value(std::uint64_t tick, std::size_t d) const noexcept;
  double slope(std::uint64_t tick, std::size_t d) const noexcept;
  /// Whether the device's cubic from the last knot to a knot at tick j stays within the
  /// tolerance of every tick between.
  bool fits(std::uint64_t j) const noexcept;
  /// The knot of tick j, encoded into `out`; it becomes the last knot.
  std::size_t encode_knot(std::uint64_t j, std::uint8_t* out) noexcept;

  ByteTransport& transport_;
  AvarDeviceLinkConfig config_;
  std::string description_;
  std::string problem_;
  ActuatorTable table_;
  avar_device::Status status_{};
  avar_device::Parser parser_{};
  std::array<std::uint8_t, avar_device::kMaxFrame> parser_buffer_{};
  std::uint64_t ticks_ = 0;  ///< sends since start()
  /// The commanded values of the last ticks (output units, device order): ring_frames_ frames,
  /// tick k at k % ring_frames_.
  std::vector<double> ring_;
  std::size_t ring_frames_ = 0;
  /// The last knot: its tick, values and slopes (output units per second) as the device has them.
  bool knotted_ = false;
  std::uint64_t last_knot_ = 0;
  std::vector<double> knot_values_, knot_slopes_;
  std::size_t min_spacing_ = 1;  ///< ticks between knots at the least (the device's room)
  std::vector<avar_device::Knot> knots_;
  std::vector<std::uint8_t> packet_;
  std::size_t last_send_size_ = 0;
  Reconnector reconnector_;
};

}  // namespace avar::firmware_iface
