// avar-device: `avar-device: {knot_ms, lead_ms, device_rate, device_knots, device_watchdog_ms}` on
// a serial port, or port: sim. Each actuator is one of the device's outputs (0, 1, ... one per
// channel) with the servo pulse range the device drives it over, in µs.
#include <algorithm>

#include "schema_entries.hpp"
#include "setting_reading.hpp"

namespace avar::rig {
namespace {

LinkOptions parse_avar_device(const LinkSpec&, const LinkSettings& s) {
  s.expect_only_keys({"knot_ms", "lead_ms", "device_rate", "device_knots", "device_watchdog_ms"});
  AvarDeviceOptions o;
  if (const ScalarValue* v = s.find("knot_ms")) o.knot_ms = static_cast<int>(integer_in(*v, "knot_ms", 1, 1000, "ms"));
  if (const ScalarValue* v = s.find("lead_ms")) {
    o.lead_ms = static_cast<int>(integer_in(*v, "lead_ms", 1, 2000, "ms"));
    // Two knots and a tick (a tick is at most a knot's spacing) ahead: a knot reaches the device
    // before its time comes.
    if (o.lead_ms < 3 * o.knot_ms)
      v->fail("expected lead_ms of at least 3 knots (" + std::to_string(3 * o.knot_ms) + " ms with knot_ms " +
              std::to_string(o.knot_ms) + "), found " + v->describe());
  } else if (o.lead_ms < 3 * o.knot_ms) {
    o.lead_ms = 3 * o.knot_ms;
  }
  if (const ScalarValue* v = s.find("device_rate"))
    o.device_rate_hz = static_cast<int>(integer_in(*v, "device_rate", 1, 10000, "control ticks per second"));
  if (const ScalarValue* v = s.find("device_watchdog_ms"))
    o.device_watchdog_ms = static_cast<int>(integer_in(*v, "device_watchdog_ms", 0, 60000, "ms (0: none)"));
  const int needed = o.lead_ms / o.knot_ms + 2;
  if (const ScalarValue* v = s.find("device_knots")) {
    o.device_knots = static_cast<int>(integer_in(*v, "device_knots", 2, 255, "knot frames"));
    if (o.device_knots < needed)
      v->fail("expected device_knots of at least " + std::to_string(needed) + " (a lead of " + std::to_string(o.lead_ms) +
              " ms with a knot every " + std::to_string(o.knot_ms) + " ms), found " + v->describe());
  } else if (o.device_knots < needed) {
    o.device_knots = std::min(needed, 255);
  }
  return o;
}

}  // namespace

const ProtocolSchema& avar_device_schema() {
  static const ProtocolSchema p{
      .name = "avar-device",
      .device_name = "avar device",
      .default_baud = 115200,
      .bauds_text = "any standard rate the device's sketch opens (115200 by default)",
      .device_accepts_baud = [](int) { return true; },
      .parse = parse_avar_device,
      .address_rule = [](const LinkSpec&, bool) -> AddressRule {
        return {"output", 0, 60, "min_us", "max_us", "trim_us", 100, 5000, "µs"};
      },
      .needs_calibration = true,
      .reports_telemetry = [](const LinkSpec&) { return false; },
  };
  return p;
}

}  // namespace avar::rig
