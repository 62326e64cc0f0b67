#include "avar/assembly/ssc32_protocol.hpp"

#include <chrono>
#include <cmath>

#include "avar/sim/sim_ssc32.hpp"

namespace avar::assembly {
namespace {

SimulatedDevice simulated_ssc32(const rig::Rig& rig, std::size_t link) {
  sim::SimSsc32Config config;
  config.baud = rig.links[link].baud;
  auto device = std::make_unique<sim::SimSsc32>(config);
  sim::SimSsc32* d = device.get();
  return {std::move(device),
          [d](const rig::ActuatorSpec& a) { return a.calibration.to_channel(d->servo_position_us(a.device_channel)); }};
}

}  // namespace

firmware_iface::Ssc32LinkConfig ssc32_config(const rig::Rig& rig, std::size_t link) {
  firmware_iface::Ssc32LinkConfig config;
  config.baud = rig.links[link].baud;
  // Each group move lasts one tick, so the servos glide between the ticks' positions.
  config.move_time = std::chrono::milliseconds(static_cast<long>(std::lround(1000.0 / rig.rate_hz)));
  for (const rig::ActuatorSpec& a : rig.actuators_on(rig::LinkIndex{link})) {
    firmware_iface::Ssc32Actuator s;
    s.channel = a.channel.value;
    s.device_channel = a.device_channel;
    s.calibration = a.calibration;
    if (a.speed_limit) s.speed_us_per_s = *a.speed_limit * a.calibration.device_per_unit();
    config.actuators.push_back(s);
  }
  return config;
}

const Protocol& ssc32_protocol() {
  static const Protocol p{
      "ssc32",
      "SSC-32",
      9600,
      "2400, 9600, 38400, 115200",
      [](int baud) { return baud == 2400 || baud == 9600 || baud == 38400 || baud == 115200; },
      [](const rig::LinkSpec& link) { link.settings.expect_only_keys({}); },
      [](const rig::LinkSpec&, bool) -> AddressRule {
        return {"device_channel", 0, 31, "min_us", "max_us", "trim_us", 500, 2500, "µs"};
      },
      false,
      true,
      [](const rig::LinkSpec&) { return false; },
      [](const rig::Rig& rig, std::size_t link, firmware_iface::ByteTransport& transport,
         const DriverTuning&) -> std::unique_ptr<firmware_iface::ActuatorLink> {
        return std::make_unique<firmware_iface::Ssc32Link>(transport, ssc32_config(rig, link));
      },
      simulated_ssc32,
  };
  return p;
}

}  // namespace avar::assembly
