#include "avar/assembly/gpio_protocol.hpp"

#include <stdexcept>

namespace avar::assembly {

firmware_iface::GpioLinkConfig gpio_config(const rig::Rig& rig, std::size_t link, const std::string& chip) {
  firmware_iface::GpioLinkConfig config;
  config.description = "GPIO link '" + rig.links[link].name + "' on " + chip;
  for (const rig::ActuatorSpec& a : rig.actuators_on(rig::LinkIndex{link})) {
    firmware_iface::GpioOutput o;
    o.channel = a.channel.value;
    o.line = static_cast<unsigned>(a.device_channel);
    o.active_low = a.options_as<rig::GpioOutputOptions>().active_low;
    o.calibration = a.calibration;
    o.initial = a.calibration.to_device(rig.channel(a.channel).rest) >= 0.5;
    config.outputs.push_back(o);
  }
  return config;
}

const Protocol& gpio_protocol() {
  static const Protocol p{
      .name = "gpio",
      .open =
          [](const rig::Rig& rig, std::size_t link, LinkEndpoint at) {
            if (!at.chip) throw std::logic_error("gpio link '" + rig.links[link].name + "' is opened on its chip");
            firmware_iface::GpioLinkConfig config = gpio_config(rig, link, at.chip->describe());
            OpenedLink opened;
            opened.driver = std::make_unique<firmware_iface::GpioLink>(std::move(at.chip), std::move(config));
            return opened;
          },
      .make_simulated = nullptr,
      .on_gpio_chip = true,
      .sim =
          {
              .name = "gpio",
              .alias = nullptr,
              .summary = "Simulated GPIO chip lines (relays, valves, LEDs), inside the avar that drives them",
              .description =
                  "A GPIO chip whose output lines switch digital channels (a relay, a valve, an LED) and whose input "
                  "lines are buttons and e-stops. A simulated chip has no device node another program could open: it "
                  "lives inside the avar process that drives it. Give the link port: sim in the rig, or run with --sim.",
              .transport = SimTransport::in_process,
              .example = "  avar play examples/shows/haunt-prop.yaml --rig examples/rigs/haunt-prop.yaml --sim",
              .options = {},
          },
  };
  return p;
}

}  // namespace avar::assembly
