// PCA9685: `pca9685: {address, frequency, clock, outputs}` on the I2C bus the port names
// (/dev/i2c-1), or port: sim. Each actuator is an output 0..15 with its pulse range in µs.
#include "schema_entries.hpp"
#include "setting_reading.hpp"

namespace avar::rig {
namespace {

LinkOptions parse_pca9685(const LinkSpec&, const LinkSettings& s) {
  s.expect_only_keys({"address", "frequency", "clock", "outputs"});
  Pca9685Options o;
  if (const ScalarValue* v = s.find("address"))
    o.address = static_cast<int>(integer_in(*v, "address", 0x03, 0x77, "(7-bit I2C addresses; 64 is 0x40)"));
  if (const ScalarValue* v = s.find("clock")) o.clock_hz = integer_in(*v, "clock", 1000000, 50000000, "Hz");
  // The prescale reaches clock / (4096 x 256) to clock / (4096 x 4).
  const long long lowest = o.clock_hz / (4096LL * 256) + 1, highest = o.clock_hz / (4096LL * 4);
  if (const ScalarValue* v = s.find("frequency"))
    o.frequency_hz = static_cast<int>(integer_in(*v, "frequency", lowest, highest, "Hz"));
  if (const ScalarValue* v = s.find("outputs")) {
    const std::string kind = v->as_string("outputs");
    if (kind != "totem_pole" && kind != "open_drain")
      v->fail("expected outputs: totem_pole (the boards') or open_drain, found " + v->describe());
    o.totem_pole = kind == "totem_pole";
  }
  return o;
}

}  // namespace

const ProtocolSchema& pca9685_schema() {
  static const ProtocolSchema p{
      .name = "pca9685",
      .device_name = "PCA9685 board",
      .default_baud = 0,
      .bauds_text = "none (an I2C board has no baud rate)",
      .device_accepts_baud = [](int) { return true; },
      .parse = parse_pca9685,
      .address_rule = [](const LinkSpec&, bool) -> AddressRule {
        return {"output", 0, 15, "min_us", "max_us", "trim_us", 100, 5000, "µs"};
      },
      .needs_calibration = true,
      .reports_telemetry = [](const LinkSpec&) { return false; },
  };
  return p;
}

}  // namespace avar::rig
