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

/// `avar sim ssc32`: an SSC-32U with its 32 channels.
ServedDevice standalone_ssc32(const SimValues&) {
  auto device = std::make_unique<sim::SimSsc32>(sim::SimSsc32Config{});
  const sim::SimSsc32* d = device.get();
  ServedDevice out;
  out.description = "simulated SSC-32U (32 channels)";
  out.state = [d] {
    std::string line = "outputs (µs):";
    for (int ch = 0; ch < 12; ++ch) line += " " + std::to_string(std::lround(d->output_pulse(ch)));
    return line;
  };
  out.device = std::move(device);
  return out;
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
      .name = "ssc32",
      .open =
          [](const rig::Rig& figure, std::size_t index, LinkEndpoint at) {
            return open_over_bytes(figure, index, at,
                                   [](const rig::Rig& rig, std::size_t link, firmware_iface::ByteTransport& transport,
                                      const DriverTuning&) -> std::unique_ptr<firmware_iface::ActuatorLink> {
                                     return std::make_unique<firmware_iface::Ssc32Link>(transport, ssc32_config(rig, link));
                                   });
          },
      .make_simulated = simulated_ssc32,
      .sim =
          {
              .name = "ssc32",
              .alias = nullptr,
              .summary = "A simulated Lynxmotion SSC-32U (32 hobby servos, ASCII commands)",
              .description = "A Lynxmotion SSC-32U servo controller: ASCII group moves (#<ch>P<µs>S<speed>T<ms>), "
                             "query of movement status and pulse widths, 32 channels of hobby servo pulses.",
              .transport = SimTransport::pty,
              .example = "  avar sim ssc32                        # prints /dev/pts/N\n"
                         "  avar play SHOW.yaml --rig RIG.yaml --port /dev/pts/N    # a rig whose link says ssc32: {}",
              .options = {},
              .make = standalone_ssc32,
          },
  };
  return p;
}

}  // namespace avar::assembly
