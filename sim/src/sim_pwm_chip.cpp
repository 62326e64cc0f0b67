#include "avar/sim/sim_pwm_chip.hpp"

#include <stdexcept>

namespace avar::sim {

void SimPwmChip::open_output(unsigned output, std::uint32_t period_ns) {
  std::lock_guard lock(mutex_);
  if (output >= outputs_.size())
    throw std::runtime_error(description_ + " has outputs 0 to " + std::to_string(outputs_.size() - 1) + ", not " +
                             std::to_string(output));
  if (outputs_[output].opened) throw std::runtime_error(description_ + ": output " + std::to_string(output) + " is opened twice");
  if (period_ns == 0) throw std::runtime_error(description_ + ": output " + std::to_string(output) + " needs a period");
  outputs_[output] = Output{true, false, period_ns, 0, 0};
}

Status SimPwmChip::set_pulse(unsigned output, std::uint32_t pulse_ns) noexcept {
  std::lock_guard lock(mutex_);
  if (output >= outputs_.size() || !outputs_[output].opened || pulse_ns > outputs_[output].period_ns) return Status::out_of_range;
  if (failing_) return Status::io_error;
  Output& o = outputs_[output];
  o.pulse_ns = pulse_ns;
  o.on = true;
  ++o.changes;
  return Status::ok;
}

Status SimPwmChip::switch_off(unsigned output) noexcept {
  std::lock_guard lock(mutex_);
  if (output >= outputs_.size() || !outputs_[output].opened) return Status::out_of_range;
  if (failing_) return Status::io_error;
  outputs_[output].on = false;
  ++outputs_[output].changes;
  return Status::ok;
}

void SimPwmChip::set_failing(bool failing) {
  std::lock_guard lock(mutex_);
  failing_ = failing;
}

double SimPwmChip::pulse_us(unsigned output) const {
  std::lock_guard lock(mutex_);
  if (output >= outputs_.size() || !outputs_[output].on) return 0;
  return outputs_[output].pulse_ns / 1000.0;
}

std::uint32_t SimPwmChip::period_ns(unsigned output) const {
  std::lock_guard lock(mutex_);
  return output < outputs_.size() ? outputs_[output].period_ns : 0;
}

std::uint64_t SimPwmChip::changes(unsigned output) const {
  std::lock_guard lock(mutex_);
  return output < outputs_.size() ? outputs_[output].changes : 0;
}

}  // namespace avar::sim
