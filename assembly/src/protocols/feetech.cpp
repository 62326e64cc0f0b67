#include "avar/assembly/feetech_protocol.hpp"

#include <chrono>
#include <cmath>

#include "avar/sim/sim_feetech.hpp"

namespace avar::assembly {
namespace {

ServoBusOptions feetech_bus(const rig::LinkSpec& link) { return servo_bus_options(link, {"series"}); }

firmware_iface::FeetechReadback feetech_readback(Readback r) {
  switch (r) {
    case Readback::none: return firmware_iface::FeetechReadback::none;
    case Readback::position: return firmware_iface::FeetechReadback::position;
    case Readback::full: break;
  }
  return firmware_iface::FeetechReadback::full;
}

/// Simulated Feetech servos with the rig's IDs and series, each parked at its rest pose.
SimulatedDevice simulated_feetech(const rig::Rig& rig, std::size_t link) {
  sim::SimFeetechConfig config;
  config.series = feetech_series(rig.links[link]);
  config.baud = rig.links[link].baud;
  for (const rig::ActuatorSpec& a : rig.actuators_on(rig::LinkIndex{link})) {
    sim::SimFeetechServo servo;
    servo.id = static_cast<std::uint8_t>(a.device_channel);
    servo.initial_position = std::round(a.calibration.to_device(rig.channel(a.channel).rest));
    config.servos.push_back(servo);
  }
  auto device = std::make_unique<sim::SimFeetech>(config);
  sim::SimFeetech* d = device.get();
  return {std::move(device),
          [d, &rig](const rig::ActuatorSpec& a) { return a.calibration.to_channel(d->position(index_on_link(rig, a))); }};
}

}  // namespace

firmware_iface::feetech::Series feetech_series(const rig::LinkSpec& link) {
  const ScalarValue* series = link.settings.find("series");
  if (!series) return firmware_iface::feetech::Series::sts;
  const std::string name = series->as_string("the Feetech series");
  if (name == "scs") return firmware_iface::feetech::Series::scs;
  if (name != "sts") series->fail("unknown Feetech series " + series->describe() + "; expected one of: sts, scs");
  return firmware_iface::feetech::Series::sts;
}

firmware_iface::FeetechLinkConfig feetech_config(const rig::Rig& rig, std::size_t link) {
  const rig::LinkSpec& spec = rig.links[link];
  const ServoBusOptions bus = feetech_bus(spec);
  firmware_iface::FeetechLinkConfig config;
  config.series = feetech_series(spec);
  config.baud = spec.baud;
  config.readback = feetech_readback(bus.readback);
  config.reply_timeout = std::chrono::milliseconds(bus.reply_timeout_ms);
  for (const rig::ActuatorSpec& a : rig.actuators_on(rig::LinkIndex{link})) {
    firmware_iface::FeetechActuator f;
    f.channel = a.channel.value;
    f.id = static_cast<std::uint8_t>(a.device_channel);
    f.calibration = a.calibration;
    // Device-side limits are given in channel units; the servo counts in position steps.
    if (a.speed_limit) f.speed_steps_per_s = *a.speed_limit * a.calibration.device_per_unit();
    if (a.acceleration_limit) f.acceleration_steps_per_s2 = *a.acceleration_limit * a.calibration.device_per_unit();
    config.actuators.push_back(f);
  }
  return config;
}

const Protocol& feetech_protocol() {
  static const Protocol p{
      "feetech",
      "Feetech",
      1000000,
      "38400, 57600, 115200, 500000, 1000000",
      [](int baud) {
        for (int b : {38400, 57600, 115200, 500000, 1000000})
          if (baud == b) return true;
        return false;
      },
      [](const rig::LinkSpec& link) {
        (void)feetech_bus(link);
        (void)feetech_series(link);
      },
      [](const rig::LinkSpec& link, bool) -> AddressRule {
        const bool scs = feetech_series(link) == firmware_iface::feetech::Series::scs;
        return {"id", 0, 253, "min_position", "max_position", "trim", 0, scs ? 1023.0 : 4095.0, "position steps"};
      },
      false,
      true,
      [](const rig::LinkSpec& link) { return feetech_bus(link).readback != Readback::none; },
      [](const rig::Rig& rig, std::size_t link, firmware_iface::ByteTransport& transport,
         const DriverTuning& tuning) -> std::unique_ptr<firmware_iface::ActuatorLink> {
        firmware_iface::FeetechLinkConfig config = feetech_config(rig, link);
        config.reply_timeout = tuning.reply_timeout(config.reply_timeout);
        return std::make_unique<firmware_iface::FeetechLink>(transport, config);
      },
      simulated_feetech,
  };
  return p;
}

}  // namespace avar::assembly
