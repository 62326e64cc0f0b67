#include "avar/assembly/gpio_protocol.hpp"

#include <stdexcept>

namespace avar::assembly {
namespace {

/// The highest line offset a rig may name; each chip checks its own count when opened.
constexpr long long kMaxLine = 1023;

void check_gpio_actuator(const rig::Rig& rig, const rig::ActuatorSpec& a) {
  const rig::ChannelSpec& ch = rig.channel(a.channel);
  if (!ch.digital())
    ScalarValue{"", false, "an analog channel", a.where}.fail("a gpio line switches a digital channel, but channel '" + ch.name +
                                                              "' is analog; give it kind: digital (0 off, 1 on)");
  if (const ScalarValue* low = a.settings.find("active_low")) (void)low->as_bool("active_low");
  if (a.speed_limit || a.acceleration_limit)
    ScalarValue{"", false, "a speed or acceleration limit", a.where}.fail(
        "a gpio line switches at once; speed and acceleration do not apply to actuators on link '" + rig.link(a.link).name + "'");
}

}  // namespace

firmware_iface::GpioLinkConfig gpio_config(const rig::Rig& rig, std::size_t link, const std::string& chip) {
  firmware_iface::GpioLinkConfig config;
  config.description = "GPIO link '" + rig.links[link].name + "' on " + chip;
  for (const rig::ActuatorSpec& a : rig.actuators_on(rig::LinkIndex{link})) {
    firmware_iface::GpioOutput o;
    o.channel = a.channel.value;
    o.line = static_cast<unsigned>(a.device_channel);
    const ScalarValue* low = a.settings.find("active_low");
    o.active_low = low && low->as_bool("active_low");
    o.calibration = a.calibration;
    o.initial = a.calibration.to_device(rig.channel(a.channel).rest) >= 0.5;
    config.outputs.push_back(o);
  }
  return config;
}

const Protocol& gpio_protocol() {
  static const Protocol p = [] {
    Protocol g{
        "gpio",
        "GPIO chip",
        0,
        "none (a GPIO chip has no baud rate)",
        [](int) { return true; },
        [](const rig::LinkSpec& link) { link.settings.expect_only_keys({}); },
        [](const rig::LinkSpec&, bool) -> AddressRule { return {"line", 0, kMaxLine, nullptr, nullptr, nullptr, 0, 1, "level"}; },
        false,
        false,
        [](const rig::LinkSpec&) { return false; },
        [](const rig::Rig& rig, std::size_t link, firmware_iface::ByteTransport&,
           const DriverTuning&) -> std::unique_ptr<firmware_iface::ActuatorLink> {
          throw std::logic_error("gpio link '" + rig.links[link].name + "' is opened on its chip, not a serial port");
        },
        [](const rig::Rig& rig, std::size_t link) -> SimulatedDevice {
          throw std::logic_error("gpio link '" + rig.links[link].name + "' is simulated by a simulated chip, not a byte device");
        },
    };
    g.actuator_keys = {"active_low"};
    g.check_actuator = check_gpio_actuator;
    g.port_is_serial = [](const rig::LinkSpec&, const std::string&) { return false; };
    g.make_chip_link = [](const rig::Rig& rig, std::size_t link,
                          std::shared_ptr<firmware_iface::GpioChip> chip) -> std::unique_ptr<firmware_iface::ActuatorLink> {
      firmware_iface::GpioLinkConfig config = gpio_config(rig, link, chip->describe());
      return std::make_unique<firmware_iface::GpioLink>(std::move(chip), std::move(config));
    };
    return g;
  }();
  return p;
}

}  // namespace avar::assembly
