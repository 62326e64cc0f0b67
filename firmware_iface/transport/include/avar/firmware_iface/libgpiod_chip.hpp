#pragma once
// Real GPIO chips through libgpiod (v1.6 API): avar::transport_gpio, the one library that links
// libgpiod. The seam they implement is gpio_chip.hpp.

#include <memory>
#include <string>
#include <vector>

#include "avar/firmware_iface/gpio_chip.hpp"

namespace avar::firmware_iface {

/// Opens a GPIO chip through libgpiod by name (gpiochip0), number (0), label (pinctrl-bcm2711)
/// or path (/dev/gpiochip0). Throws std::runtime_error naming the chip and what is missing:
/// "no GPIO chip 'gpiochip0' (this machine has none: /dev/gpiochip* absent)", or the chips there
/// are. Not real-time.
std::unique_ptr<GpioChip> open_gpio_chip(const std::string& name);

/// The GPIO chips this machine has (/dev/gpiochip*), by name, sorted; empty when none.
std::vector<std::string> gpio_chip_names();

}  // namespace avar::firmware_iface
