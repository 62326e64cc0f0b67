// DYNAMIXEL and Feetech: the polled smart-servo buses and the settings they share.
#include <initializer_list>
#include <vector>

#include "schema_entries.hpp"

namespace avar::rig {
namespace {

ServoBusOptions servo_bus(const LinkSettings& s, std::initializer_list<std::string_view> extra_keys) {
  std::vector<std::string_view> keys(extra_keys);
  for (std::string_view k : {"readback", "reply_timeout_ms", "retries"}) keys.push_back(k);
  s.expect_only_keys(keys);
  ServoBusOptions bus;
  if (const ScalarValue* r = s.find("readback")) {
    const std::string mode = r->as_string("readback");
    if (mode == "none") bus.readback = Readback::none;
    else if (mode == "position") bus.readback = Readback::position;
    else if (mode == "full") bus.readback = Readback::full;
    else r->fail("unknown readback " + r->describe() + "; expected one of: none, position, full");
  }
  if (const ScalarValue* t = s.find("reply_timeout_ms")) {
    const long long ms = t->as_integer("reply_timeout_ms");
    if (ms < 1 || ms > 1000) t->fail("expected reply_timeout_ms from 1 to 1000, found " + t->describe());
    bus.reply_timeout_ms = static_cast<int>(ms);
  }
  if (const ScalarValue* r = s.find("retries")) {
    const long long n = r->as_integer("retries");
    if (n < 0 || n > 10) r->fail("expected retries from 0 to 10, found " + r->describe());
    bus.retries = static_cast<int>(n);
  }
  return bus;
}

FeetechSeries feetech_series(const LinkSettings& s) {
  const ScalarValue* series = s.find("series");
  if (!series) return FeetechSeries::sts;
  const std::string name = series->as_string("the Feetech series");
  if (name == "scs") return FeetechSeries::scs;
  if (name != "sts") series->fail("unknown Feetech series " + series->describe() + "; expected one of: sts, scs");
  return FeetechSeries::sts;
}

bool one_of(int baud, std::initializer_list<int> rates) {
  for (int b : rates)
    if (baud == b) return true;
  return false;
}

}  // namespace

const ProtocolSchema& dynamixel_schema() {
  static const ProtocolSchema p{
      .name = "dynamixel",
      .device_name = "DYNAMIXEL",
      .default_baud = 57600,
      .bauds_text = "9600, 57600, 115200, 1000000, 2000000, 3000000, 4000000",
      .device_accepts_baud =
          [](int baud) {
            return one_of(baud, {9600, 57600, 115200, 1000000, 2000000, 3000000, 4000000});
          },
      .parse = [](const LinkSpec&, const LinkSettings& s) -> LinkOptions { return DynamixelOptions{servo_bus(s, {})}; },
      .address_rule = [](const LinkSpec&, bool) -> AddressRule {
        return {"id", 0, 252, "min_position", "max_position", "trim", 0, 4095, "position pulses"};
      },
      .needs_calibration = true,
      .reports_telemetry =
          [](const LinkSpec& link) { return link.options_as<DynamixelOptions>().bus.readback != Readback::none; },
  };
  return p;
}

const ProtocolSchema& feetech_schema() {
  static const ProtocolSchema p{
      .name = "feetech",
      .device_name = "Feetech",
      .default_baud = 1000000,
      .bauds_text = "38400, 57600, 115200, 500000, 1000000",
      .device_accepts_baud =
          [](int baud) {
            return one_of(baud, {38400, 57600, 115200, 500000, 1000000});
          },
      .parse = [](const LinkSpec&, const LinkSettings& s) -> LinkOptions {
        FeetechOptions o;
        o.bus = servo_bus(s, {"series"});
        o.series = feetech_series(s);
        return o;
      },
      .address_rule = [](const LinkSpec& link, bool) -> AddressRule {
        const bool scs = link.options_as<FeetechOptions>().series == FeetechSeries::scs;
        return {"id", 0, 253, "min_position", "max_position", "trim", 0, scs ? 1023.0 : 4095.0, "position steps"};
      },
      .needs_calibration = true,
      .reports_telemetry = [](const LinkSpec& link) { return link.options_as<FeetechOptions>().bus.readback != Readback::none; },
  };
  return p;
}

}  // namespace avar::rig
