#include "avar/assembly/digital_inputs.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>

namespace avar::assembly {
namespace {

inputs::GpioInputRole role_of(rig::InputRole r) {
  switch (r) {
    case rig::InputRole::estop: return inputs::GpioInputRole::estop;
    case rig::InputRole::control: return inputs::GpioInputRole::control;
    case rig::InputRole::start: return inputs::GpioInputRole::start;
  }
  return inputs::GpioInputRole::control;
}

}  // namespace

std::unique_ptr<inputs::GpioInputs> open_digital_inputs(const rig::Rig& rig, GpioChips& chips) {
  if (rig.digital_inputs.empty()) return nullptr;
  std::vector<inputs::GpioInputConfig> configs;
  const rig::DigitalInputSpec* current = nullptr;
  try {
    for (const rig::DigitalInputSpec& in : rig.digital_inputs) {
      current = &in;
      inputs::GpioInputConfig c;
      c.name = in.name;
      c.chip = chips.open(in.chip);
      if (in.line >= c.chip->line_count())
        throw std::runtime_error(c.chip->describe() + " has " + std::to_string(c.chip->line_count()) + " lines (0 to " +
                                 std::to_string(c.chip->line_count() - 1) + "); line " + std::to_string(in.line) +
                                 " does not exist");
      c.request.line = in.line;
      c.request.active_low = in.active_low;
      c.request.bias = in.bias;
      c.debounce = std::chrono::nanoseconds(std::llround(in.debounce_s * 1e9));
      c.role = role_of(in.role);
      configs.push_back(std::move(c));
    }
    current = nullptr;
    return std::make_unique<inputs::GpioInputs>(std::move(configs));
  } catch (const std::runtime_error& e) {
    // A failed request names the chip and the line; point at the input that asked for it.
    const rig::DigitalInputSpec& at = current ? *current : rig.digital_inputs.front();
    throw InputError({rig.file, at.where.line, at.where.column}, "digital input: " + std::string(e.what()));
  }
}

}  // namespace avar::assembly
