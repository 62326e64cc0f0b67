#pragma once
// The driver layer as the control loop sees it: one link (a serial port, a bus) carrying several
// actuators, each bound to one channel of the rig. The loop hands it whole frames of channel
// values; the link picks its actuators, calibrates, encodes and exchanges once per tick.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "avar/core/status.hpp"

namespace avar::firmware_iface {

class ActuatorLink {
 public:
  virtual ~ActuatorLink() = default;

  /// Prepares the device (clears latched errors, sends speed/acceleration limits). May block
  /// for replies; called once before the loop starts. Not real-time.
  virtual Status start() = 0;

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
};

}  // namespace avar::firmware_iface
