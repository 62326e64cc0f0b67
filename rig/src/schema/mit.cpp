// MIT mini-cheetah style actuators ("MIT mode") on a CAN link: a model or its ranges, and gains.
#include <array>
#include <numbers>

#include "avar/core/format.hpp"
#include "avar/firmware_iface/can_frame.hpp"
#include "schema_entries.hpp"
#include "setting_reading.hpp"

namespace avar::rig {
namespace {

namespace mit = firmware_iface::mit;

constexpr std::array<std::string_view, 8> kMitKeys{"model", "p_max", "v_max", "t_max", "kp_max", "kd_max", "kp", "kd"};

/// The motor model's value ranges: a named model, then any bound given on its own (symmetric).
mit::MitRanges ranges_of(const LinkSettings& s) {
  mit::MitRanges r = mit::kMiniCheetahRanges;
  if (const ScalarValue* m = s.find("model")) {
    const mit::MitRanges* named = mit::find_ranges(m->as_string("model"));
    if (!named) {
      std::string names;
      for (const auto& n : mit::kNamedRanges) names += (names.empty() ? "" : ", ") + std::string(n.name);
      m->fail("unknown MIT motor model " + m->describe() + "; expected one of: " + names +
              " (or give p_max, v_max, t_max, kp_max and kd_max)");
    }
    r = *named;
  }
  const auto bound = [&](const char* key, double low, double high, const char* unit, double* min, double* max) {
    if (const ScalarValue* v = s.find(key)) {
      *max = number_in(*v, key, low, high, unit);
      if (min) *min = -*max;
    }
  };
  bound("p_max", 0.1, 1e4, "rad", &r.p_min, &r.p_max);
  bound("v_max", 0.1, 1e4, "rad/s", &r.v_min, &r.v_max);
  bound("t_max", 0.01, 1e4, "N·m", &r.t_min, &r.t_max);
  bound("kp_max", 0.01, 1e5, "N·m/rad", nullptr, &r.kp_max);
  bound("kd_max", 0.001, 1e4, "N·m·s/rad", nullptr, &r.kd_max);
  return r;
}

double gain_of(const LinkSettings& s, const char* key, double max, double fallback, const char* unit) {
  const ScalarValue* v = s.find(key);
  return v ? number_in(*v, std::string(key) + " (at most the model's " + key + "_max)", 0, max, unit) : std::min(fallback, max);
}

ActuatorOptions parse_mit(const LinkSettings& s, int, const SourceLocation&) {
  MitOptions o;
  o.ranges = ranges_of(s);
  o.kp = gain_of(s, "kp", o.ranges.kp_max, 20, "N·m/rad");
  o.kd = gain_of(s, "kd", o.ranges.kd_max, 0.5, "N·m·s/rad");
  return o;
}

void validate_mit(const ActuatorSpec& a) {
  const mit::MitRanges& r = a.options_as<MitOptions>().ranges;
  const double low = a.calibration.device_low(), high = a.calibration.device_high();
  if (low < r.p_min || high > r.p_max)
    ScalarValue{"", false, "nothing", a.where}.fail(
        "the channel's range takes this MIT motor from " + format_number(low) + " to " + format_number(high) +
        " rad, outside its model's position range ±" + format_number(r.p_max) +
        " rad; expected a smaller gear_ratio, another zero, or a model with a wider p_max");
}

}  // namespace

const CanDriveSchema& mit_schema() {
  static const CanDriveSchema p{
      "mit",
      "MIT motor",
      1,
      firmware_iface::kCanMaxStandardId,
      "rad",
      "any (each motor's firmware sets its own; 1000000 is usual)",
      [](int) { return true; },
      [] { return std::span<const std::string_view>(kMitKeys); },
      parse_mit,
      [](const ActuatorSpec&) { return 2 * std::numbers::pi; },
      validate_mit,
      [](const ActuatorSpec& a, const CanOptions& bus, std::vector<CanIdRange>& out) {
        const auto node = static_cast<std::uint32_t>(a.device_channel);
        out.push_back({node, node, false});
        out.push_back({bus.mit_master_id, bus.mit_master_id, true});  // every motor replies there
      },
  };
  return p;
}

}  // namespace avar::rig
