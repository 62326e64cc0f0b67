#pragma once
// Live input devices (gamepads, MIDI controllers, OSC senders) as named controls. Each device
// runs on its own thread and delivers every change to a ControlSink; the control loop reads the
// latest values from there (avar::control::ControlMailbox), so no device ever blocks a tick.
//
// Values are normalised: bipolar controls (stick axes, pitch bend, hat axes) run -1..1 with 0 at
// rest; unipolar ones (faders, triggers, knobs, buttons, notes, OSC values) run 0..1. A control
// mapped to a channel (`inputs:` in a rig) says how that range spans the channel.

#include <cstdint>
#include <string>
#include <string_view>

namespace avar::inputs {

/// Where input devices deliver control values.
class ControlSink {
 public:
  virtual ~ControlSink() = default;
  /// A control moved. Called on an input device's thread (several devices: several threads);
  /// quick, never blocks. `control` is valid for the call only. `bipolar`: the value's range is
  /// -1..1 (else 0..1). `arrived_ns`: CLOCK_MONOTONIC when the device's message arrived.
  virtual void post(std::string_view control, double value, bool bipolar, std::int64_t arrived_ns) noexcept = 0;
};

/// Messages an input source has taken and ignored (malformed, unknown address, wrong type).
struct InputCounters {
  std::uint64_t messages = 0;
  std::uint64_t ignored = 0;
};

/// An input device and the thread that reads it.
class InputSource {
 public:
  virtual ~InputSource() = default;
  /// Opens the device and starts delivering into `sink` (borrowed: it must outlive stop()).
  /// Throws std::runtime_error naming the device and what is missing (no such port, no device
  /// with that vendor and product id, the address in use). Called once.
  virtual void start(ControlSink& sink) = 0;
  /// Stops the thread and closes the device; no post() after it returns. Idempotent; the
  /// destructor calls it.
  virtual void stop() noexcept = 0;
  /// "OSC on udp 127.0.0.1:9000", "MIDI 'nanoKONTROL2 MIDI 1'", "HID 054c:09cc Wireless Controller".
  virtual std::string describe() const = 0;
  /// Safe from any thread.
  virtual InputCounters counters() const noexcept = 0;
};

}  // namespace avar::inputs
