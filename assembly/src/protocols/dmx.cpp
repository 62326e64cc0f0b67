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

/// `avar sim dmx`: a DMX USB Pro widget with one universe.
ServedDevice standalone_dmx(const SimValues&) {
  auto device = std::make_unique<sim::SimDmx>(sim::SimDmxConfig{});
  const sim::SimDmx* d = device.get();
  ServedDevice out;
  out.description = "simulated DMX USB Pro (one universe)";
  out.state = [d] {
    std::string line = std::to_string(d->frames_received()) + " frames; slots:";
    for (int address = 1; address <= 16; ++address) line += " " + std::to_string(d->slot(address));
    return line;
  };
  out.device = std::move(device);
  return out;
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
      .name = "dmx",
      .open =
          [](const rig::Rig& figure, std::size_t index, LinkEndpoint at) {
            return open_over_bytes(figure, index, at,
                                   [](const rig::Rig& rig, std::size_t link, firmware_iface::ByteTransport& transport,
                                      const DriverTuning&) -> std::unique_ptr<firmware_iface::ActuatorLink> {
                                     return std::make_unique<firmware_iface::DmxLink>(transport, dmx_config(rig, link));
                                   });
          },
      .make_simulated = simulated_dmx,
      .sim =
          {
              .name = "dmx",
              .alias = nullptr,
              .summary = "A simulated ENTTEC DMX USB Pro widget (one DMX universe)",
              .description = "An ENTTEC DMX USB Pro widget: it takes Output Only Send DMX messages and holds the "
                             "universe's 512 slots, as servo decoders and dimmers on the DMX line would see them.",
              .transport = SimTransport::pty,
              .example = "  avar sim dmx                          # prints /dev/pts/N\n"
                         "  avar play SHOW.yaml --rig RIG.yaml --port /dev/pts/N    # a rig whose link says dmx: {}",
              .options = {},
              .make = standalone_dmx,
          },
  };
  return p;
}

}  // namespace avar::assembly
