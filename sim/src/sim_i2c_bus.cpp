#include "avar/sim/sim_i2c_bus.hpp"

#include <stdexcept>

namespace avar::sim {

namespace pca9685 = firmware_iface::pca9685;

void SimI2cBus::add_pca9685(std::uint8_t address) {
  const std::lock_guard lock(mutex_);
  Board& b = boards_[address];
  pca9685::power_on(b.registers);
}

void SimI2cBus::set_answering(std::uint8_t address, bool answering) {
  const std::lock_guard lock(mutex_);
  const auto found = boards_.find(address);
  if (found == boards_.end()) throw std::invalid_argument("no simulated board at address " + std::to_string(address));
  found->second.answering = answering;
}

Status SimI2cBus::write(std::uint8_t address, std::span<const std::uint8_t> bytes) noexcept {
  const std::lock_guard lock(mutex_);
  const auto found = boards_.find(address);
  if (found == boards_.end() || !found->second.answering) return Status::io_error;
  Board& b = found->second;
  b.writes.emplace_back(bytes.begin(), bytes.end());
  return pca9685::apply(b.registers, bytes.data(), bytes.size()) ? Status::ok : Status::io_error;
}

void SimI2cBus::settle(std::uint32_t us) {
  const std::lock_guard lock(mutex_);
  settled_us_ += us;
}

std::uint64_t SimI2cBus::settled_us() const {
  const std::lock_guard lock(mutex_);
  return settled_us_;
}

pca9685::Registers SimI2cBus::registers(std::uint8_t address) const {
  const std::lock_guard lock(mutex_);
  return boards_.at(address).registers;
}

double SimI2cBus::pulse_us(std::uint8_t address, std::uint8_t output, std::uint32_t clock_hz) const {
  const pca9685::Registers r = registers(address);
  const double counts = pca9685::pulse_counts(r, output);
  return counts * (r.value[pca9685::kPreScale] + 1.0) / clock_hz * 1e6;
}

std::vector<std::vector<std::uint8_t>> SimI2cBus::writes(std::uint8_t address) const {
  const std::lock_guard lock(mutex_);
  return boards_.at(address).writes;
}

}  // namespace avar::sim
