#include "avar/assembly/maestro_protocol.hpp"

#include <algorithm>
#include <stdexcept>

#include "avar/assembly/servo_bus_options.hpp"
#include "avar/firmware_iface/libusb_control_transport.hpp"
#include "avar/sim/sim_maestro.hpp"
#include "avar/sim/sim_maestro_usb.hpp"
#include <cstdio>

#include "../sim_option_checks.hpp"

namespace avar::assembly {
namespace {

constexpr const char* kModels[] = {"micro6", "mini12", "mini18", "mini24"};

const char* model_name(int channel_count) {
  switch (channel_count) {
    case 6: return kModels[0];
    case 12: return kModels[1];
    case 18: return kModels[2];
    default: return kModels[3];
  }
}

/// The settings of a simulated Maestro set up as its owner would have set up the real one: the
/// rig's channel count, framing and CRC, each used channel's pulse range opened to the actuator's
/// window, and every servo parked at its rest pose (where the last soft stop left it).
sim::SimMaestroConfig simulated_maestro_config(const rig::Rig& rig, std::size_t link, const rig::MaestroOptions& options) {
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
  return config;
}

/// The link's Maestro, simulated: on a serial port, or on USB when the link says usb.
SimulatedDevice simulated_maestro(const rig::Rig& rig, std::size_t link) {
  const rig::MaestroOptions& options = rig.links[link].options_as<rig::MaestroOptions>();
  const sim::SimMaestroConfig config = simulated_maestro_config(rig, link, options);
  SimulatedDevice out;
  if (options.usb) {
    auto device = std::make_unique<sim::SimMaestroUsb>(config, options.usb_serial.empty() ? "00000000" : options.usb_serial);
    const sim::SimMaestroUsb* d = device.get();
    out.true_position = [d](const rig::ActuatorSpec& a) {
      return a.calibration.to_channel(d->servo_position_us(a.device_channel));
    };
    out.usb_name = "USB (serial " + d->serial() + ")";
    out.usb_device = std::move(device);
  } else {
    auto device = std::make_unique<sim::SimMaestro>(config);
    const sim::SimMaestro* d = device.get();
    out.true_position = [d](const rig::ActuatorSpec& a) {
      return a.calibration.to_channel(d->servo_position_us(a.device_channel));
    };
    out.device = std::move(device);
  }
  return out;
}

/// `avar sim maestro`: a Maestro on a pseudo-terminal, as set up from the options.
ServedDevice standalone_maestro(const SimValues& values) {
  const long long channels = values.integer("channels");
  if (channels != 6 && channels != 12 && channels != 18 && channels != 24)
    throw SimOptionError("--channels: " + values.text("channels") +
                         " is not a Maestro's channel count; expected 6, 12, 18 or 24");
  const long long device_number = values.integer("device-number");
  if (device_number < 0 || device_number > 127)
    throw SimOptionError("--device-number: " + values.text("device-number") + " is outside 0 to 127");
  sim::SimMaestroConfig config;
  config.channel_count = static_cast<int>(channels);
  config.device_number = static_cast<std::uint8_t>(device_number);
  config.crc = values.flag("crc");
  auto device = std::make_unique<sim::SimMaestro>(config);
  const sim::SimMaestro* d = device.get();
  ServedDevice out;
  out.description = "simulated Maestro (" + std::to_string(channels) + " channels, device number " +
                    std::to_string(device_number) + (config.crc ? ", CRC on" : "") + ")";
  out.state = [d, channels] {
    std::string line = "outputs (µs):";
    char value[16];
    for (int ch = 0; ch < channels && ch < 12; ++ch) {
      std::snprintf(value, sizeof value, " %.0f", d->output_pulse(ch) / 4.0);
      line += value;
    }
    return line;
  };
  out.device = std::move(device);
  return out;
}

}  // namespace

firmware_iface::MaestroLinkConfig maestro_config(const rig::Rig& rig, std::size_t link) {
  const rig::MaestroOptions& options = rig.links[link].options_as<rig::MaestroOptions>();
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

firmware_iface::MaestroUsbLinkConfig maestro_usb_config(const rig::Rig& rig, std::size_t link, const DriverTuning& tuning) {
  firmware_iface::MaestroLinkConfig serial = maestro_config(rig, link);
  firmware_iface::MaestroUsbLinkConfig config;
  config.channel_count = serial.channel_count;
  config.timeout = tuning.reply_timeout(config.timeout);
  // The watchdog decides when silence is a fault: the Maestro may miss that many ticks.
  config.silent_ticks = silent_exchanges(rig, link);
  config.actuators = std::move(serial.actuators);
  return config;
}

std::unique_ptr<firmware_iface::ActuatorLink> open_maestro_usb(const rig::Rig& rig, std::size_t link) {
  const rig::LinkSpec& spec = rig.links[link];
  const rig::MaestroOptions& options = spec.options_as<rig::MaestroOptions>();
  const auto fail_at_usb = [&](const std::string& problem) { throw InputError(options.usb_where, problem); };
  namespace usb = firmware_iface::maestro_usb;
  firmware_iface::UsbDeviceQuery query{
      usb::kVendorId, {usb::kProductIds.begin(), usb::kProductIds.end()}, options.usb_serial, "Maestro"};
  std::unique_ptr<firmware_iface::LibusbControlTransport> transport;
  try {
    transport = std::make_unique<firmware_iface::LibusbControlTransport>(std::move(query));
  } catch (const std::runtime_error& e) {
    fail_at_usb("link '" + spec.name + "': " + e.what());
  }
  const int found = usb::channels_for_product_id(transport->product_id());
  if (found != options.channel_count)
    fail_at_usb("link '" + spec.name + "': the Maestro with serial " + transport->serial() + " is a " + model_name(found) +
                ", but the link says model: " + model_name(options.channel_count));
  return std::make_unique<firmware_iface::MaestroUsbLink>(std::move(transport), maestro_usb_config(rig, link, DriverTuning{}));
}

bool maestro_port_is_serial(const rig::LinkSpec& link, const std::string& port) {
  return !link.options_as<rig::MaestroOptions>().usb || !port.empty();
}

namespace {

std::unique_ptr<firmware_iface::ActuatorLink> serial_maestro(const rig::Rig& rig, std::size_t link,
                                                             firmware_iface::ByteTransport& transport, const DriverTuning&) {
  return std::make_unique<firmware_iface::MaestroLink>(transport, maestro_config(rig, link));
}

/// On USB (a simulated device's, or found by its serial number), else on its virtual serial port:
/// a port given on the command line (--port /dev/ttyACM0) opens that even when the rig says usb.
OpenedLink open_maestro(const rig::Rig& rig, std::size_t link, LinkEndpoint at) {
  if (at.usb) {
    OpenedLink opened;
    opened.driver = std::make_unique<firmware_iface::MaestroUsbLink>(std::move(at.usb), maestro_usb_config(rig, link, at.tuning));
    return opened;
  }
  if (at.bytes || at.simulated || maestro_port_is_serial(rig.links[link], at.port))
    return open_over_bytes(rig, link, at, serial_maestro);
  OpenedLink opened;
  opened.driver = open_maestro_usb(rig, link);
  return opened;
}

}  // namespace

const Protocol& maestro_protocol() {
  static const Protocol p{
      .name = "maestro",
      .open = open_maestro,
      .make_simulated = simulated_maestro,
      .sim =
          {
              .name = "maestro",
              .alias = nullptr,
              .summary = "A simulated Pololu Maestro (hobby servo controller) on a serial port",
              .description = "A Pololu Maestro servo controller (Micro 6 or Mini 12, 18, 24 channels) as its virtual serial port "
                             "answers: the compact and Pololu protocols, Set Target, speed and acceleration, Get Position, and "
                             "optionally CRC-7. Its servos move to their targets as the real ones do. A Maestro on native USB "
                             "(`usb:` in a rig) is simulated inside the avar that drives it: `avar play SHOW --rig RIG --sim`.",
              .transport = SimTransport::pty,
              .example = "  avar sim maestro --channels 12        # prints /dev/pts/N\n"
                         "  avar play examples/shows/hello-head.yaml --rig examples/rigs/hello-head.yaml --port /dev/pts/N",
              .options = {{"channels", "24", "Channel count: 6, 12, 18 or 24"},
                          {"device-number", "12", "Device number for the Pololu protocol, 0 to 127"},
                          {"crc", "", "Expect a CRC-7 byte after every command", true}},
              .make = standalone_maestro,
          },
  };
  return p;
}

}  // namespace avar::assembly
