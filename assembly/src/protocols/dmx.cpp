#include "avar/assembly/dmx_protocol.hpp"

#include "avar/sim/sim_dmx.hpp"

namespace avar::assembly {
namespace {

/// A simulated DMX widget with a servo decoder (or dimmer) on every actuator's slots; a dimmer's
/// truth is the level the widget puts out.
SimulatedDevice simulated_dmx(const rig::Rig& rig, std::size_t link) {
  sim::SimDmxConfig config;
  config.baud = rig.links[link].baud;
  for (const rig::ActuatorSpec& a : rig.actuators_on(rig::LinkIndex{link})) {
    sim::SimDmxFixture fixture;
    fixture.address = a.device_channel;
    fixture.fine = a.fine;
    config.fixtures.push_back(fixture);
  }
  auto device = std::make_unique<sim::SimDmx>(config);
  sim::SimDmx* d = device.get();
  return {std::move(device),
          [d, &rig](const rig::ActuatorSpec& a) { return a.calibration.to_channel(d->fixture_level(index_on_link(rig, a))); }};
}

}  // namespace

std::vector<firmware_iface::DmxActuator> dmx_actuators(const rig::Rig& rig, std::size_t link) {
  std::vector<firmware_iface::DmxActuator> out;
  for (const rig::ActuatorSpec& a : rig.actuators_on(rig::LinkIndex{link})) {
    firmware_iface::DmxActuator d;
    d.channel = a.channel.value;
    d.address = a.device_channel;
    d.fine = a.fine;
    d.calibration = a.calibration;
    out.push_back(d);
  }
  return out;
}

firmware_iface::DmxLinkConfig dmx_config(const rig::Rig& rig, std::size_t link) {
  firmware_iface::DmxLinkConfig config;
  config.actuators = dmx_actuators(rig, link);
  return config;
}

const Protocol& dmx_protocol() {
  static const Protocol p{
      "dmx",
      "DMX widget",
      57600,
      "any (the widget is a USB device)",
      [](int) { return true; },
      [](const rig::LinkSpec& link) { link.settings.expect_only_keys({}); },
      [](const rig::LinkSpec&, bool fine) -> AddressRule {
        return {"address", 1, fine ? 511 : 512, "min_level", "max_level", "trim", 0, fine ? 65535.0 : 255.0, "DMX level"};
      },
      true,
      false,
      [](const rig::LinkSpec&) { return false; },
      [](const rig::Rig& rig, std::size_t link, firmware_iface::ByteTransport& transport,
         const DriverTuning&) -> std::unique_ptr<firmware_iface::ActuatorLink> {
        return std::make_unique<firmware_iface::DmxLink>(transport, dmx_config(rig, link));
      },
      simulated_dmx,
  };
  return p;
}

}  // namespace avar::assembly
