#include "avar/assembly/gpio_chips.hpp"

#include "avar/firmware_iface/libgpiod_chip.hpp"

namespace avar::assembly {

sim::SimGpioChip& GpioChips::simulated(const std::string& name) {
  auto& chip = simulated_[name];
  if (!chip) chip = std::make_shared<sim::SimGpioChip>(name);
  return *chip;
}

std::shared_ptr<firmware_iface::GpioChip> GpioChips::open(const std::string& name, bool simulate) {
  if (simulate || simulates(name)) {
    simulated(name);
    return simulated_[name];
  }
  auto& chip = real_[name];
  if (!chip) chip = firmware_iface::open_gpio_chip(name);
  return chip;
}

}  // namespace avar::assembly
