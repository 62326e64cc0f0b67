#pragma once
// The driver layer as the control loop sees it: one link (a serial port, a bus) carrying several
// actuators, each bound to one channel of the rig. The loop hands it whole frames of channel
// values; the link picks its actuators, calibrates, encodes and exchanges once per tick.

#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <string>

#include "avar/core/status.hpp"

namespace avar::firmware_iface {

/// Conditions a smart actuator reports about itself (bits of ChannelTelemetry::faults).
enum DeviceFault : std::uint32_t {
  kDeviceOverheat = 1u << 0,
  kDeviceOverload = 1u << 1,
  kDeviceElectrical = 1u << 2,  ///< electrical shock, over-current
  kDeviceVoltage = 1u << 3,     ///< input voltage out of range
  kDeviceEncoder = 1u << 4,     ///< position sensor failure
  kDeviceOther = 1u << 5,
  kDeviceLost = 1u << 6,        ///< stopped answering: heartbeats or replies missed past their budget
  kDeviceFaultState = 1u << 7,  ///< the drive went to its fault state or left closed-loop control
};

/// What a device last reported of one channel. NaN for what it does not report.
struct ChannelTelemetry {
  static constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();
  double position = kUnknown;       ///< channel units
  double load = kUnknown;           ///< signed fraction of the actuator's rated torque, -1..1
  double temperature_c = kUnknown;  ///< degrees Celsius
  std::uint32_t faults = 0;         ///< DeviceFault bits, as of the last reply
  std::uint64_t updates = 0;        ///< replies that refreshed this entry since start
};

/// The health of a link's wire since start(); all counters only grow.
struct LinkCounters {
  std::uint64_t exchanges = 0;  ///< send() calls that reached the transport
  std::uint64_t bytes_sent = 0;
  std::uint64_t bytes_received = 0;
  std::uint64_t replies = 0;         ///< well-formed replies taken
  std::uint64_t crc_errors = 0;      ///< replies with a bad checksum (dropped, sync kept)
  std::uint64_t framing_errors = 0;  ///< bytes skipped to find the next packet
  std::uint64_t timeouts = 0;        ///< replies that did not come in time
  std::uint64_t retries = 0;
  std::uint64_t device_errors = 0;  ///< replies whose error field was set
  std::uint64_t reconnects = 0;     ///< transport re-opened after a failure
};

class ActuatorLink {
 public:
  virtual ~ActuatorLink() = default;

  /// Prepares the device (clears latched errors, sends speed/acceleration limits). May block
  /// for replies; called once before the loop starts. Not real-time.
  virtual Status start() = 0;

  /// After a failed start(): what was wrong beyond the Status (which servo, which setting), for
  /// the message; empty when there is nothing more to say.
  virtual std::string start_problem() const { return {}; }

  /// After a channel fault from this link's telemetry: what the device said or failed to say
  /// ("ODrive node 2: no heartbeat for 30 ticks"); empty when there is nothing more to say.
  /// Not real-time; call on the thread that calls send(), or after the loop stopped.
  virtual std::string channel_problem(std::size_t channel) const {
    static_cast<void>(channel);
    return {};
  }

  /// Reads where the device says each of this link's channels is, in channel units, into
  /// frame[channel]; sets known[channel] for those it could read. Channels the device cannot
  /// report are left untouched. Not real-time (waits for replies).
  virtual Status read_positions(std::span<double> frame, std::span<bool> known) = 0;

  /// Sends one frame of channel values (indexed by rig channel). Values are expected inside
  /// the channels' limits; the link still saturates every pulse to its actuator's window.
  /// Real-time safe: no allocation, no exception, one write to the transport.
  virtual Status send(std::span<const double> frame) noexcept = 0;

  /// Stops driving every actuator of the link (hobby servos: no more pulses, they go limp).
  /// Real-time safe.
  virtual Status release() noexcept = 0;

  /// From the next send on, stops driving this link's actuators of one channel (a fail-safe
  /// "release"); channels the link does not drive are ignored. Real-time safe; may be called
  /// from the loop thread while another thread sends.
  virtual void release_channel(std::size_t channel) noexcept = 0;

  /// Pulses saturated to an actuator's window since start (a show asked for more than the
  /// calibration allows).
  virtual std::uint64_t saturated_pulses() const noexcept = 0;

  /// A name for messages: protocol and port.
  virtual const std::string& describe() const noexcept = 0;

  /// Copies the latest telemetry of this link's channels into out[channel] (out is indexed by
  /// rig channel); other entries are left untouched. Links to devices that report nothing (hobby
  /// PWM boards, DMX) leave everything untouched. Call on the thread that calls send().
  /// Real-time safe.
  virtual void read_telemetry(std::span<ChannelTelemetry> out) const noexcept { static_cast<void>(out); }

  /// Wire counters since start(). Real-time safe; any thread (counters are relaxed atomics or
  /// snapshots in implementations).
  virtual LinkCounters counters() const noexcept { return {}; }

  /// How long after send() the device carries a command out, in seconds: 0 for a device that
  /// acts on a command as it arrives; a link that has its device play commands later (avar-device
  /// streams knots `lead` ahead) says by how much, and the tracking check compares what the
  /// device reports with the command of that long ago. Any thread.
  virtual double command_delay_s() const noexcept { return 0; }
};

}  // namespace avar::firmware_iface
