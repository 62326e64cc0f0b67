#pragma once
// The PWM seam: outputs of a PWM controller that each send one pulse per period (a hobby servo
// on a Raspberry Pi's hardware PWM, pwmchip0's pwm0 and pwm1). open_pwm_chip() (sysfs_pwm_chip.hpp,
// avar::transport_pwm) opens a real chip through Linux's sysfs PWM class; avar::sim::SimPwmChip is
// a simulated one.
//
// Threads: one thread drives the chip at a time (a link's send, or its start before the loop).

#include <cstdint>
#include <string>

#include "avar/core/status.hpp"

namespace avar::firmware_iface {

class PwmChip {
 public:
  virtual ~PwmChip() = default;
  /// Claims output `output` with a period of `period_ns`, sending nothing until set_pulse.
  /// Load-time; throws std::runtime_error naming the output and the reason.
  virtual void open_output(unsigned output, std::uint32_t period_ns) = 0;
  /// The output's high time each period (ns, at most its period), switched on if it was off.
  /// io_error when the chip refuses. Real-time safe: one or two writes to the kernel.
  virtual Status set_pulse(unsigned output, std::uint32_t pulse_ns) noexcept = 0;
  /// The output switched off: no pulses (a hobby servo goes limp). Real-time safe.
  virtual Status switch_off(unsigned output) noexcept = 0;
  /// "PWM chip /sys/class/pwm/pwmchip0", "simulated PWM chip".
  virtual const std::string& describe() const noexcept = 0;
};

}  // namespace avar::firmware_iface
