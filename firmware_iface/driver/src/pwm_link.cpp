#include "avar/firmware_iface/pwm_link.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace avar::firmware_iface {

PwmLink::PwmLink(std::shared_ptr<PwmChip> chip, PwmLinkConfig config)
    : chip_(std::move(chip)), config_(std::move(config)), table_(config_.outputs), written_(config_.outputs.size(), -1) {
  if (config_.outputs.empty()) throw std::invalid_argument(config_.description + " has no outputs");
  if (config_.frequency_hz < 1 || config_.frequency_hz > 1000)
    throw std::invalid_argument(config_.description + ": a pulse rate of " + std::to_string(config_.frequency_hz) +
                                " Hz is outside 1 to 1000 Hz");
  period_ns_ = 1000000000u / config_.frequency_hz;
  for (std::size_t i = 0; i < config_.outputs.size(); ++i) {
    const PwmOutput& o = config_.outputs[i];
    for (std::size_t j = 0; j < i; ++j)
      if (o.pin == config_.outputs[j].pin)
        throw std::invalid_argument(config_.description + ": output " + std::to_string(o.pin) + " drives two actuators");
    if (o.calibration.device_high() * 1000.0 > period_ns_ || o.calibration.device_low() < 0)
      throw std::invalid_argument(config_.description + ": output " + std::to_string(o.pin) + "'s pulses reach " +
                                  std::to_string(o.calibration.device_high()) + " µs, longer than the period at " +
                                  std::to_string(config_.frequency_hz) + " Hz");
  }
}

Status PwmLink::start() {
  for (const PwmOutput& o : config_.outputs) {
    try {
      chip_->open_output(o.pin, period_ns_);
    } catch (const std::runtime_error& e) {
      start_problem_ = e.what();
      return Status::io_error;
    }
  }
  return Status::ok;
}

Status PwmLink::read_positions(std::span<double> frame, std::span<bool> known) {
  static_cast<void>(frame);
  static_cast<void>(known);
  return Status::ok;
}

Status PwmLink::send(std::span<const double> frame) noexcept {
  counters_.add(&LinkCounters::exchanges);
  const bool all_off = all_released_.load(std::memory_order_relaxed);
  Status status = Status::ok;
  for (std::size_t i = 0; i < config_.outputs.size(); ++i) {
    std::int64_t pulse_ns = -2;  // off
    if (!all_off && !table_.released(i))
      pulse_ns = std::clamp<std::int64_t>(std::llround(table_.to_device(i, frame) * 1000.0), 0, period_ns_);
    if (written_[i] == pulse_ns) continue;
    const unsigned pin = config_.outputs[i].pin;
    const Status s = pulse_ns == -2 ? chip_->switch_off(pin) : chip_->set_pulse(pin, static_cast<std::uint32_t>(pulse_ns));
    if (s != Status::ok) {
      counters_.add(&LinkCounters::device_errors);
      status = Status::io_error;
      continue;
    }
    written_[i] = pulse_ns;
  }
  return status;
}

Status PwmLink::release() noexcept {
  all_released_.store(true, std::memory_order_relaxed);
  Status status = Status::ok;
  for (std::size_t i = 0; i < config_.outputs.size(); ++i) {
    if (written_[i] < 0) {  // off already (never switched on)
      written_[i] = -2;
      continue;
    }
    if (chip_->switch_off(config_.outputs[i].pin) != Status::ok) {
      counters_.add(&LinkCounters::device_errors);
      status = Status::io_error;
      continue;
    }
    written_[i] = -2;
  }
  return status;
}

}  // namespace avar::firmware_iface
