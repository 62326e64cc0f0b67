// Pololu Maestro: `maestro: {model, device_number, crc, baud_detect}` on a serial port, or
// `maestro: {model, usb: SERIAL}` (usb: any for the only Maestro present) on native USB.
#include <algorithm>

#include "schema_entries.hpp"

namespace avar::rig {
namespace {

int maestro_channels_for_model(const ScalarValue& model_value) {
  const std::string model = model_value.as_string("the Maestro model");
  if (model == "micro6") return 6;
  if (model == "mini12") return 12;
  if (model == "mini18") return 18;
  if (model == "mini24") return 24;
  model_value.fail("unknown Maestro model " + model_value.describe() + "; expected one of: micro6, mini12, mini18, mini24");
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

LinkOptions parse_maestro(const LinkSpec& link, const LinkSettings& s) {
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
    options.usb_where = usb->where;
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

}  // namespace

const ProtocolSchema& maestro_schema() {
  static const ProtocolSchema p{
      .name = "maestro",
      .device_name = "Maestro",
      .default_baud = 115200,
      .bauds_text = "300 to 200000",
      .device_accepts_baud = [](int baud) { return baud >= 300 && baud <= 200000; },
      .parse = parse_maestro,
      .port_optional = [](const LinkSettings& s) { return s.find("usb") != nullptr; },
      .address_rule = [](const LinkSpec& link, bool) -> AddressRule {
        return {"device_channel",
                0,
                link.options_as<MaestroOptions>().channel_count - 1,
                "min_us",
                "max_us",
                "trim_us",
                64,
                4000,
                "µs"};
      },
      .needs_calibration = true,
      // On USB the Maestro tells where each channel's pulse is, every tick.
      .reports_telemetry = [](const LinkSpec& link) { return link.options_as<MaestroOptions>().usb; },
  };
  return p;
}

}  // namespace avar::rig
