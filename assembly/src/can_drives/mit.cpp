// The registry entry of MIT mini-cheetah style actuators ("MIT mode") on a CAN link.
#include <array>
#include <numbers>

#include "avar/firmware_iface/mit_drives.hpp"
#include "avar/sim/sim_mit_motor.hpp"
#include "avar/assembly/can_protocol.hpp"
#include "can_drive_entries.hpp"

namespace avar::assembly {

const CanDriveProtocol& mit_drive() {
  static const CanDriveProtocol p{
      "mit",
      [](const rig::Rig&, std::span<const rig::ActuatorSpec* const> actuators,
         const CanBusOptions& bus) -> std::unique_ptr<firmware_iface::CanDrives> {
        firmware_iface::MitDrivesConfig config;
        config.reply_budget_ticks = bus.silent_ticks;
        config.master_id = bus.mit_master_id;
        for (const rig::ActuatorSpec* a : actuators) {
          firmware_iface::MitActuator m;
          m.channel = a->channel.value;
          m.node = static_cast<std::uint32_t>(a->device_channel);
          const rig::MitOptions& o = a->options_as<rig::MitOptions>();
          m.ranges = o.ranges;
          m.kp = o.kp;
          m.kd = o.kd;
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
        if (a) config.ranges = a->options_as<rig::MitOptions>().ranges;
        auto motor = std::make_unique<sim::SimMitMotor>(config);
        sim::SimMitMotor* raw = motor.get();
        return {std::move(motor), [raw] { return raw->position(); }};
      },
      [] {
        SimOffer offer = drive_sim_offer(
            "mit", "Simulated MIT-style (mini cheetah) motors behind a simulated SLCAN adapter",
            "  avar sim mit --ids 16                     # prints /dev/pts/N\n  avar play SHOW.yaml --rig RIG.yaml "
            "--port /dev/pts/N   # a one-link rig: can: {...}, actuators with protocol: mit, node: 16");
        offer.make = [](const SimValues& values) { return standalone_slcan(mit_drive(), values); };
        return offer;
      }(),
  };
  return p;
}

}  // namespace avar::assembly
