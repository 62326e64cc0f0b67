#include "avar/assembly/maestro_protocol.hpp"

#include <algorithm>
#include <stdexcept>

#include "avar/assembly/servo_bus_options.hpp"
#include "avar/firmware_iface/libusb_control_transport.hpp"
#include "avar/sim/sim_maestro.hpp"
#include "avar/sim/sim_maestro_usb.hpp"

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

/// The serial number string a usb setting names: letters and digits, as a Maestro's are.
std::string usb_serial(const ScalarValue& v) {
  std::string text = v.as_string("usb");
  if (text == "any") return {};
  const bool plain = text.size() <= 32 && std::all_of(text.begin(), text.end(), [](char c) {
                       return (c >= '0' && c <= '9') || (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z');
                     });
  if (!plain)
    v.fail(
        "expected usb: any (the only Maestro present) or the Maestro's serial number, letters and digits as lsusb -v "
        "shows it (such as \"00012345\"); found " +
        v.describe());
  return text;
}

/// The settings of a simulated Maestro set up as its owner would have set up the real one: the
/// rig's channel count, framing and CRC, each used channel's pulse range opened to the actuator's
/// window, and every servo parked at its rest pose (where the last soft stop left it).
sim::SimMaestroConfig simulated_maestro_config(const rig::Rig& rig, std::size_t link, const MaestroOptions& options) {
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
  const MaestroOptions options = maestro_options(rig.links[link]);
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

}  // namespace

MaestroOptions maestro_options(const rig::LinkSpec& link) {
  const rig::LinkSettings& s = link.settings;
  s.expect_only_keys({"model", "device_number", "crc", "baud_detect", "usb"});
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
  if (const ScalarValue* usb = s.find("usb")) {
    options.usb = true;
    options.usb_serial = usb_serial(*usb);
    for (const char* serial_only : {"device_number", "crc", "baud_detect"})
      if (const ScalarValue* v = s.find(serial_only))
        v->fail(std::string(serial_only) + " is a setting of the Maestro's serial port; link '" + link.name +
                "' reaches its Maestro on USB (usb: " + usb->text + "), where it does not apply: remove it, or remove usb");
    if (!link.port.empty() && !link.simulated())
      usb->fail("link '" + link.name + "' names both a port (" + link.port + ") and usb: " + usb->text +
                "; expected one of them: usb finds the Maestro by its serial number (leave out the port, or write port: "
                "sim), a port opens its virtual serial port");
  }
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
  const MaestroOptions options = maestro_options(spec);
  const ScalarValue& usb_setting = *spec.settings.find("usb");
  namespace usb = firmware_iface::maestro_usb;
  firmware_iface::UsbDeviceQuery query{
      usb::kVendorId, {usb::kProductIds.begin(), usb::kProductIds.end()}, options.usb_serial, "Maestro"};
  std::unique_ptr<firmware_iface::LibusbControlTransport> transport;
  try {
    transport = std::make_unique<firmware_iface::LibusbControlTransport>(std::move(query));
  } catch (const std::runtime_error& e) {
    usb_setting.fail("link '" + spec.name + "': " + e.what());
  }
  const int found = usb::channels_for_product_id(transport->product_id());
  if (found != options.channel_count)
    usb_setting.fail("link '" + spec.name + "': the Maestro with serial " + transport->serial() + " is a " + model_name(found) +
                     ", but the link says model: " + model_name(options.channel_count));
  return std::make_unique<firmware_iface::MaestroUsbLink>(std::move(transport), maestro_usb_config(rig, link, DriverTuning{}));
}

const Protocol& maestro_protocol() {
  static const Protocol p = [] {
    Protocol m{
        "maestro",
        "Maestro",
        115200,
        "300 to 200000",
        [](int baud) { return baud >= 300 && baud <= 200000; },
        validate_maestro,
        maestro_address,
        false,
        true,
        // On USB the Maestro tells where each channel's pulse is, every tick.
        [](const rig::LinkSpec& link) { return maestro_options(link).usb; },
        [](const rig::Rig& rig, std::size_t link, firmware_iface::ByteTransport& transport,
           const DriverTuning&) -> std::unique_ptr<firmware_iface::ActuatorLink> {
          return std::make_unique<firmware_iface::MaestroLink>(transport, maestro_config(rig, link));
        },
        simulated_maestro,
    };
    m.port_optional = [](const rig::LinkSpec& link) { return link.settings.find("usb") != nullptr; };
    // A port given on the command line (--port /dev/ttyACM0) opens the Maestro's virtual serial
    // port even when the rig finds it on USB.
    m.port_is_serial = [](const rig::LinkSpec& link, const std::string& port) {
      return !maestro_options(link).usb || !port.empty();
    };
    m.open_link = [](const rig::Rig& rig, std::size_t link, const std::string&) { return open_maestro_usb(rig, link); };
    m.make_usb_link = [](const rig::Rig& rig, std::size_t link, std::unique_ptr<firmware_iface::UsbControlTransport> transport,
                         const DriverTuning& tuning) -> std::unique_ptr<firmware_iface::ActuatorLink> {
      return std::make_unique<firmware_iface::MaestroUsbLink>(std::move(transport), maestro_usb_config(rig, link, tuning));
    };
    return m;
  }();
  return p;
}

}  // namespace avar::assembly
