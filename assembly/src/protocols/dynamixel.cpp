#include "avar/assembly/dynamixel_protocol.hpp"

#include <chrono>
#include <cmath>

#include "avar/sim/sim_dynamixel.hpp"

namespace avar::assembly {
namespace {

firmware_iface::DynamixelReadback dynamixel_readback(Readback r) {
  switch (r) {
    case Readback::none: return firmware_iface::DynamixelReadback::none;
    case Readback::position: return firmware_iface::DynamixelReadback::position;
    case Readback::full: break;
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

}  // namespace

firmware_iface::DynamixelLinkConfig dynamixel_config(const rig::Rig& rig, std::size_t link) {
  const ServoBusOptions bus = servo_bus_options(rig.links[link]);
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
      "dynamixel",
      "DYNAMIXEL",
      57600,
      "9600, 57600, 115200, 1000000, 2000000, 3000000, 4000000",
      [](int baud) {
        for (int b : {9600, 57600, 115200, 1000000, 2000000, 3000000, 4000000})
          if (baud == b) return true;
        return false;
      },
      [](const rig::LinkSpec& link) { (void)servo_bus_options(link); },
      [](const rig::LinkSpec&, bool) -> AddressRule {
        return {"id", 0, 252, "min_position", "max_position", "trim", 0, 4095, "position pulses"};
      },
      false,
      true,
      [](const rig::LinkSpec& link) { return servo_bus_options(link).readback != Readback::none; },
      [](const rig::Rig& rig, std::size_t link, firmware_iface::ByteTransport& transport,
         const DriverTuning& tuning) -> std::unique_ptr<firmware_iface::ActuatorLink> {
        firmware_iface::DynamixelLinkConfig config = dynamixel_config(rig, link);
        config.reply_timeout = tuning.reply_timeout(config.reply_timeout);
        return std::make_unique<firmware_iface::DynamixelLink>(transport, config);
      },
      simulated_dynamixel,
  };
  return p;
}

}  // namespace avar::assembly
