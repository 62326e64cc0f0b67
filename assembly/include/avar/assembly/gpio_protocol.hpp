#pragma once
// Digital outputs on the lines of a GPIO chip: `gpio: {}` on a link whose port is the chip
// (gpiochip0, a label, a path, or sim). Each actuator is one line (`line: 17`, optionally
// `active_low: true`) driving a digital channel: a relay, a valve, an LED.

#include "avar/assembly/protocol.hpp"
#include "avar/firmware_iface/gpio_link.hpp"

namespace avar::assembly {

/// The outputs of gpio link `link` of a validated rig (lines requested at the channels' rest).
firmware_iface::GpioLinkConfig gpio_config(const rig::Rig& rig, std::size_t link, const std::string& chip);
const Protocol& gpio_protocol();

}  // namespace avar::assembly
