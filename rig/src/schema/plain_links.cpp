// The protocols without settings of their own: SSC-32, a USB DMX widget, GPIO output lines.
#include "schema_entries.hpp"

namespace avar::rig {
namespace {

/// The highest line offset a rig may name; each chip checks its own count when opened.
constexpr long long kMaxLine = 1023;

template <class Options>
LinkOptions no_settings(const LinkSpec&, const LinkSettings& s) {
  s.expect_only_keys({});
  return Options{};
}

void check_gpio_actuator(const Rig& rig, ActuatorSpec& a, const LinkSettings& own) {
  const ChannelSpec& ch = rig.channel(a.channel);
  if (!ch.digital())
    ScalarValue{"", false, "an analog channel", a.where}.fail("a gpio line switches a digital channel, but channel '" + ch.name +
                                                              "' is analog; give it kind: digital (0 off, 1 on)");
  GpioOutputOptions o;
  if (const ScalarValue* low = own.find("active_low")) o.active_low = low->as_bool("active_low");
  if (a.speed_limit || a.acceleration_limit)
    ScalarValue{"", false, "a speed or acceleration limit", a.where}.fail(
        "a gpio line switches at once; speed and acceleration do not apply to actuators on link '" + rig.link(a.link).name + "'");
  a.options = o;
}

}  // namespace

/// The address rule every DMX carrier shares (a widget, Art-Net, sACN).
AddressRule dmx_slot_rule(const LinkSpec&, bool fine) {
  return {"address", 1, fine ? 511 : 512, "min_level", "max_level", "trim", 0, fine ? 65535.0 : 255.0, "DMX level"};
}

const ProtocolSchema& ssc32_schema() {
  static const ProtocolSchema p{
      .name = "ssc32",
      .device_name = "SSC-32",
      .default_baud = 9600,
      .bauds_text = "2400, 9600, 38400, 115200",
      .device_accepts_baud = [](int baud) { return baud == 2400 || baud == 9600 || baud == 38400 || baud == 115200; },
      .parse = no_settings<Ssc32Options>,
      .address_rule = [](const LinkSpec&, bool) -> AddressRule {
        return {"device_channel", 0, 31, "min_us", "max_us", "trim_us", 500, 2500, "µs"};
      },
      .needs_calibration = true,
      .reports_telemetry = [](const LinkSpec&) { return false; },
  };
  return p;
}

const ProtocolSchema& dmx_schema() {
  static const ProtocolSchema p{
      .name = "dmx",
      .device_name = "DMX widget",
      .default_baud = 57600,
      .bauds_text = "any (the widget is a USB device)",
      .device_accepts_baud = [](int) { return true; },
      .parse = no_settings<DmxOptions>,
      .address_rule = dmx_slot_rule,
      .has_fine_addresses = true,
      .reports_telemetry = [](const LinkSpec&) { return false; },
  };
  return p;
}

const ProtocolSchema& gpio_schema() {
  static const ProtocolSchema p{
      .name = "gpio",
      .device_name = "GPIO chip",
      .default_baud = 0,
      .bauds_text = "none (a GPIO chip has no baud rate)",
      .device_accepts_baud = [](int) { return true; },
      .parse = no_settings<GpioOptions>,
      .address_rule = [](const LinkSpec&, bool) -> AddressRule {
        return {"line", 0, kMaxLine, nullptr, nullptr, nullptr, 0, 1, "level"};
      },
      .reports_telemetry = [](const LinkSpec&) { return false; },
      .actuator_keys = {"active_low"},
      .check_actuator = check_gpio_actuator,
  };
  return p;
}

}  // namespace avar::rig
