#include "avar/firmware_iface/pca9685_link.hpp"

#include <cmath>
#include <stdexcept>

#include "avar/firmware_iface/pca9685_codec.hpp"

namespace avar::firmware_iface {

Pca9685Link::Pca9685Link(std::shared_ptr<I2cBus> bus, Pca9685LinkConfig config)
    : bus_(std::move(bus)), config_(std::move(config)), table_(config_.outputs), written_(config_.outputs.size(), -1) {
  if (config_.outputs.empty()) throw std::invalid_argument(config_.description + " has no outputs");
  for (std::size_t i = 0; i < config_.outputs.size(); ++i) {
    if (config_.outputs[i].output >= pca9685::kChannels)
      throw std::invalid_argument(config_.description + ": output " + std::to_string(config_.outputs[i].output) +
                                  " does not exist; a PCA9685 has outputs 0 to 15");
    for (std::size_t j = 0; j < i; ++j)
      if (config_.outputs[i].output == config_.outputs[j].output)
        throw std::invalid_argument(config_.description + ": output " + std::to_string(config_.outputs[i].output) +
                                    " drives two actuators");
  }
  if (config_.address < 0x03 || config_.address > 0x77)
    throw std::invalid_argument(config_.description + ": address " + std::to_string(config_.address) +
                                " is outside the 7-bit device addresses 0x03 to 0x77");
  // The prescale's reach: within one step of the frequency asked for, 3..255.
  const double exact = static_cast<double>(config_.clock_hz) / (4096.0 * config_.frequency_hz) - 1;
  if (config_.frequency_hz == 0 || exact < pca9685::kMinPreScale - 0.5 || exact > 255.5)
    throw std::invalid_argument(config_.description + ": a pulse rate of " + std::to_string(config_.frequency_hz) +
                                " Hz is outside what the board's prescale reaches (" +
                                std::to_string(config_.clock_hz / (4096 * 256)) + " to " +
                                std::to_string(config_.clock_hz / (4096 * 4)) + " Hz)");
  prescale_ = pca9685::prescale_for(config_.clock_hz, config_.frequency_hz);
}

Status Pca9685Link::write(const std::uint8_t* bytes, std::size_t length) noexcept {
  const Status s = bus_->write(config_.address, std::span<const std::uint8_t>(bytes, length));
  if (s != Status::ok) {
    counters_.add(&LinkCounters::device_errors);
  } else {
    counters_.add(&LinkCounters::bytes_sent, length);
  }
  return s;
}

Status Pca9685Link::start() {
  pca9685::Write steps[5];
  const std::size_t n = pca9685::start_sequence(prescale_, config_.totem_pole, steps);
  for (std::size_t i = 0; i < n; ++i) {
    if (write(steps[i].bytes, steps[i].length) != Status::ok) {
      start_problem_ = "the PCA9685 at address " + std::to_string(config_.address) + " on " + bus_->describe() +
                       " does not answer (check the address jumpers, the wiring and the board's power)";
      return Status::io_error;
    }
    if (steps[i].wait_us) bus_->settle(steps[i].wait_us);
  }
  const pca9685::Write off = pca9685::all_off();
  return write(off.bytes, off.length);
}

Status Pca9685Link::read_positions(std::span<double> frame, std::span<bool> known) {
  static_cast<void>(frame);
  static_cast<void>(known);
  return Status::ok;
}

Status Pca9685Link::send(std::span<const double> frame) noexcept {
  counters_.add(&LinkCounters::exchanges);
  const bool all_off = all_released_.load(std::memory_order_relaxed);
  Status status = Status::ok;
  for (std::size_t i = 0; i < config_.outputs.size(); ++i) {
    const std::uint8_t output = config_.outputs[i].output;
    int counts = -2;  // fully off
    if (!all_off && !table_.released(i)) {
      const double pulse_us = table_.to_device(i, frame);
      const auto pulse_ns = static_cast<std::uint32_t>(std::lround(std::max(0.0, pulse_us) * 1000.0));
      counts = pca9685::counts_for_pulse_ns(pulse_ns, config_.clock_hz, prescale_);
    }
    if (written_[i] == counts) continue;
    const pca9685::Write w =
        counts == -2 ? pca9685::channel_off(output) : pca9685::channel_pulse(output, static_cast<std::uint16_t>(counts));
    if (write(w.bytes, w.length) != Status::ok) {
      status = Status::io_error;
      continue;
    }
    written_[i] = counts;
    output_writes_.fetch_add(1, std::memory_order_relaxed);
  }
  return status;
}

Status Pca9685Link::release() noexcept {
  all_released_.store(true, std::memory_order_relaxed);
  const pca9685::Write off = pca9685::all_off();
  const Status s = write(off.bytes, off.length);
  if (s == Status::ok)
    for (int& w : written_) w = -2;
  return s;
}

}  // namespace avar::firmware_iface
