// The registry entry of ODrive axes (CAN Simple, firmware 0.5.x) on a CAN link.
#include <array>
#include <cmath>

#include "../setting_reading.hpp"
#include "avar/firmware_iface/odrive_drives.hpp"
#include "avar/sim/sim_odrive_axis.hpp"
#include "can_drive_entries.hpp"

namespace avar::assembly {
namespace {

namespace odrive = firmware_iface::odrive;

constexpr std::array<std::string_view, 2> kOdriveKeys{"current_limit", "input_mode"};

odrive::InputMode input_mode_of(const rig::ActuatorSpec& a) {
  const ScalarValue* m = a.settings.find("input_mode");
  if (!m) return odrive::InputMode::passthrough;
  const std::string mode = m->as_string("input_mode");
  if (mode == "passthrough") return odrive::InputMode::passthrough;
  if (mode == "pos_filter") return odrive::InputMode::pos_filter;
  if (mode == "trap_traj") return odrive::InputMode::trap_traj;
  m->fail("unknown ODrive input_mode " + m->describe() + "; expected one of: passthrough, pos_filter, trap_traj");
}

double current_limit_of(const rig::ActuatorSpec& a) {
  const ScalarValue* c = a.settings.find("current_limit");
  return c ? number_in(*c, "current_limit", 0.1, 200, "A") : 10.0;
}

/// The axis's own velocity limit (turns/s): the actuator's speed, or 1.5 times its channel's
/// max_velocity, so that avar's limiter, not the drive, shapes every move.
double velocity_limit_of(const rig::Rig& rig, const rig::ActuatorSpec& a) {
  const double speed = a.speed_limit ? *a.speed_limit : 1.5 * rig.channel(a.channel).max_velocity;
  return speed * a.calibration.device_per_unit();
}

}  // namespace

const CanDriveProtocol& odrive_drive() {
  static const CanDriveProtocol p{
      "odrive",
      "ODrive",
      0,
      odrive::kMaxNode,
      "turns",
      "125000, 250000, 500000, 1000000",
      [](int bitrate) { return bitrate == 125'000 || bitrate == 250'000 || bitrate == 500'000 || bitrate == 1'000'000; },
      [] { return std::span<const std::string_view>(kOdriveKeys); },
      [](const rig::ActuatorSpec& a) {
        static_cast<void>(input_mode_of(a));
        static_cast<void>(current_limit_of(a));
      },
      [](const rig::ActuatorSpec&) { return 1.0; },
      [](const rig::ActuatorSpec& a, const CanBusOptions&, std::vector<CanIdRange>& out) {
        const auto node = static_cast<std::uint32_t>(a.device_channel);
        out.push_back({node << 5, (node << 5) | 0x1F, false});
      },
      [](const rig::Rig& rig, std::span<const rig::ActuatorSpec* const> actuators,
         const CanBusOptions& bus) -> std::unique_ptr<firmware_iface::CanDrives> {
        firmware_iface::OdriveDrivesConfig config;
        config.heartbeat_budget_ticks = bus.silent_ticks;
        config.tick_period_s = 1.0 / rig.rate_hz;
        for (const rig::ActuatorSpec* a : actuators) {
          firmware_iface::OdriveActuator o;
          o.channel = a->channel.value;
          o.node = static_cast<std::uint8_t>(a->device_channel);
          o.calibration = a->calibration;
          o.velocity_limit = velocity_limit_of(rig, *a);
          o.current_limit = current_limit_of(*a);
          o.input_mode = input_mode_of(*a);
          config.actuators.push_back(o);
        }
        return std::make_unique<firmware_iface::OdriveDrives>(config);
      },
      [](const rig::ActuatorSpec*, std::uint32_t node, double position, const CanBusOptions& bus) -> SimulatedDrive {
        sim::SimOdriveAxisConfig config;
        config.node = static_cast<std::uint8_t>(node);
        config.heartbeat_period_s = bus.heartbeat_ms / 1000.0;
        config.initial_position_turns = position;
        auto axis = std::make_unique<sim::SimOdriveAxis>(config);
        sim::SimOdriveAxis* raw = axis.get();
        return {std::move(axis), [raw] { return raw->position_turns(); }};
      },
  };
  return p;
}

}  // namespace avar::assembly
