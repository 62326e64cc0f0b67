#pragma once
// A simulated PWM chip: each output's period, pulse and on/off as the link set them, for a test
// or the simulator to read (a servo on an output follows its pulse). An output can be told to
// fail (a chip whose driver went away) and then refuses every change.

#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include "avar/firmware_iface/pwm_chip.hpp"

namespace avar::sim {

class SimPwmChip final : public firmware_iface::PwmChip {
 public:
  /// A chip with outputs 0 .. outputs - 1.
  explicit SimPwmChip(unsigned outputs = 256) : outputs_(outputs) {}

  void open_output(unsigned output, std::uint32_t period_ns) override;
  Status set_pulse(unsigned output, std::uint32_t pulse_ns) noexcept override;
  Status switch_off(unsigned output) noexcept override;
  const std::string& describe() const noexcept override { return description_; }

  /// Every change fails from now on (true), or works again.
  void set_failing(bool failing);
  /// The output's pulse in µs while it is on; 0 while it is off or never opened.
  double pulse_us(unsigned output) const;
  std::uint32_t period_ns(unsigned output) const;
  /// Changes made to the output (pulses set and switch-offs), since it was opened.
  std::uint64_t changes(unsigned output) const;

 private:
  struct Output {
    bool opened = false, on = false;
    std::uint32_t period_ns = 0, pulse_ns = 0;
    std::uint64_t changes = 0;
  };
  mutable std::mutex mutex_;
  std::vector<Output> outputs_;
  bool failing_ = false;
  std::string description_ = "simulated PWM chip";
};

}  // namespace avar::sim
