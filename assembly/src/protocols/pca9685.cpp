#include "avar/assembly/pca9685_protocol.hpp"

#include <cstdio>
#include <stdexcept>

namespace avar::assembly {

firmware_iface::Pca9685LinkConfig pca9685_config(const rig::Rig& rig, std::size_t link, const std::string& bus) {
  const rig::LinkSpec& spec = rig.links[link];
  const auto& o = spec.options_as<rig::Pca9685Options>();
  firmware_iface::Pca9685LinkConfig config;
  config.address = static_cast<std::uint8_t>(o.address);
  config.frequency_hz = static_cast<std::uint32_t>(o.frequency_hz);
  config.clock_hz = static_cast<std::uint32_t>(o.clock_hz);
  config.totem_pole = o.totem_pole;
  char address[8];
  std::snprintf(address, sizeof address, "0x%02x", o.address);
  config.description = "PCA9685 link '" + spec.name + "' at " + address + " on " + bus;
  for (const rig::ActuatorSpec& a : rig.actuators_on(rig::LinkIndex{link}))
    config.outputs.push_back({a.channel.value, static_cast<std::uint8_t>(a.device_channel), a.calibration});
  return config;
}

const Protocol& pca9685_protocol() {
  static const Protocol p{
      .name = "pca9685",
      .open =
          [](const rig::Rig& rig, std::size_t link, LinkEndpoint at) {
            if (!at.i2c) throw std::logic_error("pca9685 link '" + rig.links[link].name + "' is opened on its I2C bus");
            firmware_iface::Pca9685LinkConfig config = pca9685_config(rig, link, at.i2c->describe());
            OpenedLink opened;
            opened.driver = std::make_unique<firmware_iface::Pca9685Link>(std::move(at.i2c), std::move(config));
            return opened;
          },
      .make_simulated = nullptr,
      .on_i2c_bus = true,
      .sim =
          {
              .name = "pca9685",
              .alias = nullptr,
              .summary = "A simulated PCA9685 servo board on an I2C bus, inside the avar that drives it",
              .description = "A PCA9685 16-channel PWM board (the common hobby-servo board) at its address on a simulated I2C "
                             "bus: it applies each write as the chip does, and the servos' pulses are what its registers say. A "
                             "simulated bus has no device node another program could open: it lives inside the avar process that "
                             "drives it. Give the link port: sim in the rig, or run with --sim.",
              .transport = SimTransport::in_process,
              .example = "  avar play examples/shows/hello-head.yaml --rig examples/rigs/pca9685-head.yaml --sim",
              .options = {},
          },
  };
  return p;
}

}  // namespace avar::assembly
