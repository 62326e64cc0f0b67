#pragma once
// A rig's digital inputs (`digital_inputs:`: e-stop, limit switches, start buttons) opened on
// their GPIO chips, ready to start: inputs::GpioInputs is the class a program starts and
// stops, whose estop() flag goes to control::RunOptions::estop. Load-time only.

#include <memory>

#include "avar/assembly/gpio_chips.hpp"
#include "avar/inputs/gpio_inputs.hpp"
#include "avar/rig/rig.hpp"

namespace avar::assembly {

/// The watcher of every digital input of a validated rig, its lines requested on chips from
/// `chips` (share them with LinkSelection::gpio_chips so that simulated inputs and outputs are one
/// chip), not yet started; nullptr when the rig has none. Throws InputError at the input when
/// its chip is absent or its line cannot be requested.
std::unique_ptr<inputs::GpioInputs> open_digital_inputs(const rig::Rig& rig, GpioChips& chips);

}  // namespace avar::assembly
