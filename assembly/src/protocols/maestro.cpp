#include "avar/assembly/maestro_protocol.hpp"

#include "avar/sim/sim_maestro.hpp"

namespace avar::assembly {
namespace {

int maestro_channels_for_model(const ScalarValue& model_value) {
  const std::string model = model_value.as_string("the Maestro model");
  if (model == "micro6") return 6;
  if (model == "mini12") return 12;
  if (model == "mini18") return 18;
  if (model == "mini24") return 24;
  model_value.fail("unknown Maestro model " + model_value.describe() + "; expected one of: micro6, mini12, mini18, mini24");
}

void validate_maestro(const rig::LinkSpec& link) { (void)maestro_options(link); }

AddressRule maestro_address(const rig::LinkSpec& link, bool) {
  return {"device_channel", 0, maestro_options(link).channel_count - 1, "min_us", "max_us", "trim_us", 64, 4000, "µs"};
}

/// A simulated Maestro set up as its owner would have set up the real one: the rig's channel
/// count, framing and CRC, each used channel's pulse range opened to the actuator's window, and
/// every servo parked at its rest pose (where the last soft stop left it).
SimulatedDevice simulated_maestro(const rig::Rig& rig, std::size_t link) {
  const MaestroOptions options = maestro_options(rig.links[link]);
  sim::SimMaestroConfig config;
  config.channel_count = options.channel_count;
  config.device_number = options.device_number;
  config.crc = options.crc;
  config.baud_detect = options.baud_detect;
  for (const rig::ActuatorSpec& a : rig.actuators_on(rig::LinkIndex{link})) {
    auto& ch = config.channels[static_cast<std::size_t>(a.device_channel)];
    ch.min_us = a.calibration.device_low();
    ch.max_us = a.calibration.device_high();
    ch.initial_position_us = a.calibration.to_device(rig.channel(a.channel).rest);
  }
  auto device = std::make_unique<sim::SimMaestro>(config);
  sim::SimMaestro* d = device.get();
  return {std::move(device),
          [d](const rig::ActuatorSpec& a) { return a.calibration.to_channel(d->servo_position_us(a.device_channel)); }};
}

}  // namespace

MaestroOptions maestro_options(const rig::LinkSpec& link) {
  const rig::LinkSettings& s = link.settings;
  s.expect_only_keys({"model", "device_number", "crc", "baud_detect"});
  MaestroOptions options;
  if (const ScalarValue* model = s.find("model")) options.channel_count = maestro_channels_for_model(*model);
  if (const ScalarValue* dev = s.find("device_number")) {
    const long long d = dev->as_integer("the device number");
    if (d < 0 || d > 127) dev->fail("expected a device number from 0 to 127, found " + dev->describe());
    options.pololu_form = true;
    options.device_number = static_cast<std::uint8_t>(d);
  }
  if (const ScalarValue* crc = s.find("crc")) options.crc = crc->as_bool("crc");
  if (const ScalarValue* bd = s.find("baud_detect")) options.baud_detect = bd->as_bool("baud_detect");
  return options;
}

firmware_iface::MaestroLinkConfig maestro_config(const rig::Rig& rig, std::size_t link) {
  const MaestroOptions options = maestro_options(rig.links[link]);
  firmware_iface::MaestroLinkConfig config;
  config.framing.pololu = options.pololu_form;
  config.framing.device_number = options.device_number;
  config.framing.crc = options.crc;
  config.channel_count = options.channel_count;
  config.baud_detect = options.baud_detect;
  for (const rig::ActuatorSpec& a : rig.actuators_on(rig::LinkIndex{link})) {
    firmware_iface::MaestroActuator m{a.channel.value, a.device_channel, a.calibration, {}, {}};
    // Device-side limits are given in channel units; the Maestro counts in pulse width.
    if (a.speed_limit) m.speed_us_per_s = *a.speed_limit * a.calibration.device_per_unit();
    if (a.acceleration_limit) m.acceleration_us_per_s2 = *a.acceleration_limit * a.calibration.device_per_unit();
    config.actuators.push_back(m);
  }
  return config;
}

const Protocol& maestro_protocol() {
  static const Protocol p{
      "maestro",
      "Maestro",
      115200,
      "300 to 200000",
      [](int baud) { return baud >= 300 && baud <= 200000; },
      validate_maestro,
      maestro_address,
      false,
      true,
      [](const rig::LinkSpec&) { return false; },
      [](const rig::Rig& rig, std::size_t link, firmware_iface::ByteTransport& transport,
         const DriverTuning&) -> std::unique_ptr<firmware_iface::ActuatorLink> {
        return std::make_unique<firmware_iface::MaestroLink>(transport, maestro_config(rig, link));
      },
      simulated_maestro,
  };
  return p;
}

}  // namespace avar::assembly
