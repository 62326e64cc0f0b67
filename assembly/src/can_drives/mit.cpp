// The registry entry of MIT mini-cheetah style actuators ("MIT mode") on a CAN link.
#include <array>
#include <numbers>

#include "../setting_reading.hpp"
#include "avar/firmware_iface/mit_drives.hpp"
#include "avar/sim/sim_mit_motor.hpp"
#include "can_drive_entries.hpp"

namespace avar::assembly {
namespace {

namespace mit = firmware_iface::mit;

constexpr std::array<std::string_view, 8> kMitKeys{"model", "p_max", "v_max", "t_max", "kp_max", "kd_max", "kp", "kd"};

/// The motor model's value ranges: a named model, then any bound given on its own (symmetric).
mit::MitRanges ranges_of(const rig::ActuatorSpec& a) {
  mit::MitRanges r = mit::kMiniCheetahRanges;
  if (const ScalarValue* m = a.settings.find("model")) {
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
    if (const ScalarValue* v = a.settings.find(key)) {
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

double gain_of(const rig::ActuatorSpec& a, const char* key, double max, double fallback, const char* unit) {
  const ScalarValue* v = a.settings.find(key);
  return v ? number_in(*v, std::string(key) + " (at most the model's " + key + "_max)", 0, max, unit) : std::min(fallback, max);
}

void validate_mit(const rig::ActuatorSpec& a) {
  const mit::MitRanges r = ranges_of(a);
  gain_of(a, "kp", r.kp_max, 20, "N·m/rad");
  gain_of(a, "kd", r.kd_max, 0.5, "N·m·s/rad");
  const double low = a.calibration.device_low(), high = a.calibration.device_high();
  if (low < r.p_min || high > r.p_max)
    ScalarValue{"", false, "nothing", a.where}.fail(
        "the channel's range takes this MIT motor from " + format_number(low) + " to " + format_number(high) +
        " rad, outside its model's position range ±" + format_number(r.p_max) +
        " rad; expected a smaller gear_ratio, another zero, or a model with a wider p_max");
}

}  // namespace

const CanDriveProtocol& mit_drive() {
  static const CanDriveProtocol p{
      "mit",
      "MIT motor",
      1,
      firmware_iface::kCanMaxStandardId,
      "rad",
      "any (each motor's firmware sets its own; 1000000 is usual)",
      [](int) { return true; },
      [] { return std::span<const std::string_view>(kMitKeys); },
      validate_mit,
      [](const rig::ActuatorSpec&) { return 2 * std::numbers::pi; },
      [](const rig::ActuatorSpec& a, const CanBusOptions& bus, std::vector<CanIdRange>& out) {
        const auto node = static_cast<std::uint32_t>(a.device_channel);
        out.push_back({node, node, false});
        out.push_back({bus.mit_master_id, bus.mit_master_id, true});  // every motor replies there
      },
      [](const rig::Rig&, std::span<const rig::ActuatorSpec* const> actuators,
         const CanBusOptions& bus) -> std::unique_ptr<firmware_iface::CanDrives> {
        firmware_iface::MitDrivesConfig config;
        config.reply_budget_ticks = bus.silent_ticks;
        config.master_id = bus.mit_master_id;
        for (const rig::ActuatorSpec* a : actuators) {
          firmware_iface::MitActuator m;
          m.channel = a->channel.value;
          m.node = static_cast<std::uint32_t>(a->device_channel);
          m.ranges = ranges_of(*a);
          m.kp = gain_of(*a, "kp", m.ranges.kp_max, 20, "");
          m.kd = gain_of(*a, "kd", m.ranges.kd_max, 0.5, "");
          m.calibration = a->calibration;
          config.actuators.push_back(m);
        }
        return std::make_unique<firmware_iface::MitDrives>(config);
      },
      [](const rig::ActuatorSpec* a, std::uint32_t node, double position, const CanBusOptions& bus) -> SimulatedDrive {
        sim::SimMitMotorConfig config;
        config.id = node;
        config.master_id = bus.mit_master_id;
        config.initial_position = position;
        if (a) config.ranges = ranges_of(*a);
        auto motor = std::make_unique<sim::SimMitMotor>(config);
        sim::SimMitMotor* raw = motor.get();
        return {std::move(motor), [raw] { return raw->position(); }};
      },
  };
  return p;
}

}  // namespace avar::assembly
