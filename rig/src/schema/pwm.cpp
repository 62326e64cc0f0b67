// PWM: `pwm: {frequency}` on the PWM chip the port names (pwmchip0, /sys/class/pwm/pwmchip0), or
// port: sim. Each actuator is one of the chip's outputs (`pin`) with its pulse range in µs. On a
// microcontroller (avar export) the pin is the board's pin number.
#include "schema_entries.hpp"
#include "setting_reading.hpp"

namespace avar::rig {
namespace {

LinkOptions parse_pwm(const LinkSpec&, const LinkSettings& s) {
  s.expect_only_keys({"frequency"});
  PwmOptions o;
  if (const ScalarValue* v = s.find("frequency"))
    o.frequency_hz = static_cast<int>(integer_in(*v, "frequency", 40, 400, "Hz (hobby servos take 50; digital ones up to 333)"));
  return o;
}

void check_pwm_actuator(const Rig& rig, ActuatorSpec& a, const LinkSettings&) {
  const LinkSpec& link = rig.link(a.link);
  const int frequency = link.options_as<PwmOptions>().frequency_hz;
  const double period_us = 1e6 / frequency;
  if (a.calibration.device_high() >= period_us)
    ScalarValue{"", false, "a pulse as long as the period", a.where}.fail(
        "output " + std::to_string(a.device_channel) + "'s pulses reach " + std::to_string(a.calibration.device_high()) +
        " µs, but link '" + link.name + "' sends one pulse every " + std::to_string(period_us) + " µs (" +
        std::to_string(frequency) + " Hz); lower max_us or the frequency");
}

}  // namespace

const ProtocolSchema& pwm_schema() {
  static const ProtocolSchema p{
      .name = "pwm",
      .device_name = "PWM chip",
      .default_baud = 0,
      .bauds_text = "none (a PWM chip has no baud rate)",
      .device_accepts_baud = [](int) { return true; },
      .parse = parse_pwm,
      .address_rule = [](const LinkSpec&, bool) -> AddressRule {
        return {"pin", 0, 255, "min_us", "max_us", "trim_us", 100, 5000, "µs"};
      },
      .needs_calibration = true,
      .reports_telemetry = [](const LinkSpec&) { return false; },
      .check_actuator = check_pwm_actuator,
  };
  return p;
}

}  // namespace avar::rig
