#pragma once
// Hobby servos on a PWM chip's own outputs: `pwm: {frequency}` on a link whose port is the chip
// (pwmchip0, /sys/class/pwm/pwmchip0, or sim). Each actuator is one output (`pin: 0`) with its
// pulse range (`min_us`, `max_us`). avar export puts the same link on a board's own pins.

#include "avar/assembly/protocol.hpp"
#include "avar/firmware_iface/pwm_link.hpp"

namespace avar::assembly {

/// The outputs and settings of pwm link `link` of a validated rig, on the chip described.
firmware_iface::PwmLinkConfig pwm_config(const rig::Rig& rig, std::size_t link, const std::string& chip);
const Protocol& pwm_protocol();

}  // namespace avar::assembly
