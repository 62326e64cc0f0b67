#include "avar/assembly/feetech_protocol.hpp"

#include <chrono>
#include <cmath>

#include "avar/sim/sim_feetech.hpp"
#include "../sim_option_checks.hpp"
#include "avar/firmware_iface/feetech_codec.hpp"

namespace avar::assembly {
namespace {

firmware_iface::FeetechReadback feetech_readback(rig::Readback r) {
  switch (r) {
    case rig::Readback::none: return firmware_iface::FeetechReadback::none;
    case rig::Readback::position: return firmware_iface::FeetechReadback::position;
    case rig::Readback::full: break;
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

/// `avar sim feetech`: STS or SCS servos with the given IDs on one bus.
ServedDevice standalone_feetech(const SimValues& values) {
  const std::vector<std::uint8_t> ids = checked_ids(values, firmware_iface::feetech::kMaxId, "a Feetech ID");
  sim::SimFeetechConfig config;
  const std::string& series = values.text("series");
  if (series != "sts" && series != "scs")
    throw SimOptionError("--series: '" + series + "' is not a Feetech series; expected sts or scs");
  config.series = series == "sts" ? firmware_iface::feetech::Series::sts : firmware_iface::feetech::Series::scs;
  const long long baud = values.integer("baud");
  if (baud <= 0 || baud > 1'000'000 || sim::SimFeetech::baud_code(static_cast<int>(baud)) < 0)
    throw SimOptionError("--baud: a Feetech servo cannot run at " + values.text("baud") +
                         "; expected 1000000, 500000, 250000, 128000, 115200, 76800, 57600, 38400, 19200, 14400, 9600 or 4800");
  config.baud = static_cast<int>(baud);
  for (std::uint8_t id : ids) {
    sim::SimFeetechServo servo;
    servo.id = id;
    config.servos.push_back(servo);
  }
  auto device = std::make_unique<sim::SimFeetech>(config);
  const sim::SimFeetech* d = device.get();
  ServedDevice out;
  out.description = "simulated Feetech " + std::string(series == "sts" ? "STS" : "SCS") + " bus (IDs " + id_list(ids) + ", " +
                    std::to_string(baud) + " baud)";
  out.state = [d, count = ids.size()] {
    std::string line = "positions:";
    for (std::size_t i = 0; i < count && i < 8; ++i) line += " " + std::to_string(std::lround(d->position(i)));
    return line;
  };
  out.device = std::move(device);
  return out;
}

}  // namespace

firmware_iface::feetech::Series feetech_series(const rig::LinkSpec& link) {
  return link.options_as<rig::FeetechOptions>().series == rig::FeetechSeries::scs ? firmware_iface::feetech::Series::scs
                                                                                  : firmware_iface::feetech::Series::sts;
}

firmware_iface::FeetechLinkConfig feetech_config(const rig::Rig& rig, std::size_t link) {
  const rig::LinkSpec& spec = rig.links[link];
  const rig::ServoBusOptions& bus = spec.options_as<rig::FeetechOptions>().bus;
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
      .name = "feetech",
      .open =
          [](const rig::Rig& figure, std::size_t index, LinkEndpoint at) {
            return open_over_bytes(figure, index, at,
                                   [](const rig::Rig& rig, std::size_t link, firmware_iface::ByteTransport& transport,
                                      const DriverTuning& tuning) -> std::unique_ptr<firmware_iface::ActuatorLink> {
                                     firmware_iface::FeetechLinkConfig config = feetech_config(rig, link);
                                     config.reply_timeout = tuning.reply_timeout(config.reply_timeout);
                                     return std::make_unique<firmware_iface::FeetechLink>(transport, config);
                                   });
          },
      .make_simulated = simulated_feetech,
      .sim =
          {
              .name = "feetech",
              .alias = nullptr,
              .summary = "Simulated Feetech STS or SCS servos on one bus",
              .description = "Feetech serial bus servos: STS (12-bit, little-endian) or SCS (10-bit, big-endian) sharing "
                             "one half-duplex bus: ping, read, write, sync write, with goal position, speed and "
                             "acceleration; each reports position, load and temperature.",
              .transport = SimTransport::pty,
              .example = "  avar sim feetech --ids 1,2 --series sts   # prints /dev/pts/N\n"
                         "  avar play examples/shows/arm-wave.yaml --rig examples/rigs/feetech-arm.yaml --port /dev/pts/N",
              .options = {{"ids", "1", "Servo IDs on the bus, comma-separated"},
                          {"series", "sts", "sts (little-endian) or scs (big-endian)"},
                          {"baud", "1000000", "Bus rate the servos are set to"}},
              .make = standalone_feetech,
          },
  };
  return p;
}

}  // namespace avar::assembly
