// The registry entry of ODrive axes (CAN Simple, firmware 0.5.x) on a CAN link.
#include <array>
#include <cmath>

#include "avar/firmware_iface/odrive_drives.hpp"
#include "avar/sim/sim_odrive_axis.hpp"
#include "avar/assembly/can_protocol.hpp"
#include "can_drive_entries.hpp"

namespace avar::assembly {
namespace {

namespace odrive = firmware_iface::odrive;

/// The axis's own velocity limit (turns/s): the actuator's speed, or 1.5 times its channel's
/// max_velocity, so that avar's limiter, not the drive, shapes every move.
double velocity_limit_of(const rig::Rig& rig, const rig::ActuatorSpec& a) {
  const double speed = a.speed_limit ? *a.speed_limit : 1.5 * rig.channel(a.channel).max_velocity;
  return speed * a.calibration.device_per_unit();
}

odrive::InputMode input_mode_of(const rig::ActuatorSpec& a) {
  switch (a.options_as<rig::OdriveOptions>().input_mode) {
    case rig::OdriveInputMode::pos_filter: return odrive::InputMode::pos_filter;
    case rig::OdriveInputMode::trap_traj: return odrive::InputMode::trap_traj;
    case rig::OdriveInputMode::passthrough: break;
  }
  return odrive::InputMode::passthrough;
}

}  // namespace

const CanDriveProtocol& odrive_drive() {
  static const CanDriveProtocol p{
      "odrive",
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
          o.current_limit = a->options_as<rig::OdriveOptions>().current_limit;
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
      [] {
        SimOffer offer = drive_sim_offer("odrive", "Simulated ODrive axes (CAN Simple) behind a simulated SLCAN adapter",
                                         "  avar sim odrive --ids 1,2,3               # prints /dev/pts/N\n  avar play "
                                         "examples/shows/odrive-arm.yaml --rig examples/rigs/odrive-arm.yaml --port /dev/pts/N");
        offer.make = [](const SimValues& values) { return standalone_slcan(odrive_drive(), values); };
        return offer;
      }(),
  };
  return p;
}

}  // namespace avar::assembly
