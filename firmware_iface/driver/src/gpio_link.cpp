#include "avar/firmware_iface/gpio_link.hpp"

#include <stdexcept>

namespace avar::firmware_iface {

GpioLink::GpioLink(std::shared_ptr<GpioChip> chip, GpioLinkConfig config)
    : chip_(std::move(chip)), config_(std::move(config)), table_(config_.outputs), driven_(config_.outputs.size(), -1) {
  if (config_.outputs.empty()) throw std::invalid_argument(config_.description + " has no outputs");
  for (std::size_t i = 0; i < config_.outputs.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (config_.outputs[i].line == config_.outputs[j].line)
        throw std::invalid_argument(config_.description + ": line " + std::to_string(config_.outputs[i].line) +
                                    " drives two actuators");
  std::size_t requested = 0;
  try {
    for (const GpioOutput& o : config_.outputs) {
      chip_->request_output({o.line, o.active_low, o.initial});
      ++requested;
    }
  } catch (...) {
    for (std::size_t i = 0; i < requested; ++i) chip_->release(config_.outputs[i].line);
    throw;
  }
}

GpioLink::~GpioLink() {
  for (const GpioOutput& o : config_.outputs) chip_->release(o.line);
}

Status GpioLink::read_positions(std::span<double> frame, std::span<bool> known) {
  static_cast<void>(frame);
  static_cast<void>(known);
  return Status::ok;
}

Status GpioLink::send(std::span<const double> frame) noexcept {
  counters_.add(&LinkCounters::exchanges);
  const bool all_off = all_released_.load(std::memory_order_relaxed);
  Status status = Status::ok;
  for (std::size_t i = 0; i < config_.outputs.size(); ++i) {
    const bool on = !all_off && !table_.released(i) && table_.to_device(i, frame) >= 0.5;
    if (driven_[i] == (on ? 1 : 0)) continue;
    if (chip_->set(config_.outputs[i].line, on) != Status::ok) {
      counters_.add(&LinkCounters::device_errors);
      status = Status::io_error;
      continue;
    }
    driven_[i] = on ? 1 : 0;
    line_sets_.fetch_add(1, std::memory_order_relaxed);
  }
  return status;
}

Status GpioLink::release() noexcept {
  all_released_.store(true, std::memory_order_relaxed);
  Status status = Status::ok;
  for (const GpioOutput& o : config_.outputs)
    if (chip_->set(o.line, false) != Status::ok) status = Status::io_error;
  return status;
}

}  // namespace avar::firmware_iface
