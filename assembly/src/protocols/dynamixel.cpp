#include "avar/assembly/dynamixel_protocol.hpp"

#include <chrono>
#include <cmath>

#include "avar/sim/sim_dynamixel.hpp"
#include "../sim_option_checks.hpp"
#include "avar/firmware_iface/dynamixel_codec.hpp"

namespace avar::assembly {
namespace {

firmware_iface::DynamixelReadback dynamixel_readback(rig::Readback r) {
  switch (r) {
    case rig::Readback::none: return firmware_iface::DynamixelReadback::none;
    case rig::Readback::position: return firmware_iface::DynamixelReadback::position;
    case rig::Readback::full: break;
  }
  return firmware_iface::DynamixelReadback::full;
}

/// Simulated DYNAMIXEL servos with the rig's IDs, each parked at its rest pose.
SimulatedDevice simulated_dynamixel(const rig::Rig& rig, std::size_t link) {
  sim::SimDynamixelConfig config;
  for (const rig::ActuatorSpec& a : rig.actuators_on(rig::LinkIndex{link})) {
    sim::SimDynamixelServo servo;
    servo.id = static_cast<std::uint8_t>(a.device_channel);
    servo.initial_position = static_cast<std::int32_t>(std::lround(a.calibration.to_device(rig.channel(a.channel).rest)));
    config.servos.push_back(servo);
  }
  auto device = std::make_unique<sim::SimDynamixel>(config);
  sim::SimDynamixel* d = device.get();
  return {std::move(device),
          [d, &rig](const rig::ActuatorSpec& a) { return a.calibration.to_channel(d->position(index_on_link(rig, a))); }};
}

/// `avar sim dynamixel`: X-series servos with the given IDs on one bus.
ServedDevice standalone_dynamixel(const SimValues& values) {
  const std::vector<std::uint8_t> ids = checked_ids(values, firmware_iface::dynamixel::kMaxId, "a Dynamixel ID");
  sim::SimDynamixelConfig config;
  for (std::uint8_t id : ids) {
    sim::SimDynamixelServo servo;
    servo.id = id;
    config.servos.push_back(servo);
  }
  auto device = std::make_unique<sim::SimDynamixel>(config);
  const sim::SimDynamixel* d = device.get();
  ServedDevice out;
  out.description = "simulated Dynamixel bus (IDs " + id_list(ids) + ")";
  out.state = [d, count = ids.size()] {
    std::string line = "positions:";
    for (std::size_t i = 0; i < count && i < 8; ++i) line += " " + std::to_string(static_cast<long>(d->position(i)));
    return line;
  };
  out.device = std::move(device);
  return out;
}

}  // namespace

firmware_iface::DynamixelLinkConfig dynamixel_config(const rig::Rig& rig, std::size_t link) {
  const rig::ServoBusOptions& bus = rig.links[link].options_as<rig::DynamixelOptions>().bus;
  firmware_iface::DynamixelLinkConfig config;
  config.readback = dynamixel_readback(bus.readback);
  config.reply_timeout = std::chrono::milliseconds(bus.reply_timeout_ms);
  config.retries = static_cast<std::uint32_t>(bus.retries);
  // The watchdog decides when silence is a fault: a servo may miss that many exchanges.
  config.silent_exchanges = silent_exchanges(rig, link);
  for (const rig::ActuatorSpec& a : rig.actuators_on(rig::LinkIndex{link})) {
    firmware_iface::DynamixelActuator d;
    d.channel = a.channel.value;
    d.id = static_cast<std::uint8_t>(a.device_channel);
    d.calibration = a.calibration;
    d.speed_limit = a.speed_limit;
    d.acceleration_limit = a.acceleration_limit;
    config.actuators.push_back(d);
  }
  return config;
}

const Protocol& dynamixel_protocol() {
  static const Protocol p{
      .name = "dynamixel",
      .open =
          [](const rig::Rig& figure, std::size_t index, LinkEndpoint at) {
            return open_over_bytes(figure, index, at,
                                   [](const rig::Rig& rig, std::size_t link, firmware_iface::ByteTransport& transport,
                                      const DriverTuning& tuning) -> std::unique_ptr<firmware_iface::ActuatorLink> {
                                     firmware_iface::DynamixelLinkConfig config = dynamixel_config(rig, link);
                                     config.reply_timeout = tuning.reply_timeout(config.reply_timeout);
                                     return std::make_unique<firmware_iface::DynamixelLink>(transport, config);
                                   });
          },
      .make_simulated = simulated_dynamixel,
      .sim =
          {
              .name = "dynamixel",
              .alias = nullptr,
              .summary = "Simulated DYNAMIXEL X-series servos on one Protocol 2.0 bus",
              .description = "ROBOTIS DYNAMIXEL X-series servos sharing one half-duplex Protocol 2.0 bus: ping, read, "
                             "write, sync read and sync write, with torque, goal position, profile velocity and "
                             "acceleration; each reports position, load and temperature.",
              .transport = SimTransport::pty,
              .example = "  avar sim dynamixel --ids 1,2,3        # prints /dev/pts/N\n"
                         "  avar play examples/shows/arm-wave.yaml --rig examples/rigs/dynamixel-arm.yaml --port /dev/pts/N",
              .options = {{"ids", "1", "Servo IDs on the bus, comma-separated"}},
              .make = standalone_dynamixel,
          },
  };
  return p;
}

}  // namespace avar::assembly
