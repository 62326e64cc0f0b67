// The registry entry of CANopen CiA 402 servo drives (cyclic synchronous position) on a CAN link.
#include <array>
#include <cmath>

#include "avar/firmware_iface/cia402_drives.hpp"
#include "avar/sim/sim_cia402_drive.hpp"
#include "avar/assembly/can_protocol.hpp"
#include "can_drive_entries.hpp"

namespace avar::assembly {

const CanDriveProtocol& cia402_drive() {
  static const CanDriveProtocol p{
      "cia402",
      [](const rig::Rig&, std::span<const rig::ActuatorSpec* const> actuators,
         const CanBusOptions& bus) -> std::unique_ptr<firmware_iface::CanDrives> {
        firmware_iface::Cia402DrivesConfig config;
        config.heartbeat_ms = static_cast<std::uint16_t>(bus.heartbeat_ms);
        config.heartbeat_budget_ticks = bus.silent_ticks;
        for (const rig::ActuatorSpec* a : actuators) {
          firmware_iface::Cia402Actuator c;
          c.channel = a->channel.value;
          c.node = static_cast<std::uint8_t>(a->device_channel);
          c.calibration = a->calibration;
          config.actuators.push_back(c);
        }
        return std::make_unique<firmware_iface::Cia402Drives>(config);
      },
      [](const rig::ActuatorSpec* a, std::uint32_t node, double position, const CanBusOptions&) -> SimulatedDrive {
        sim::SimCia402DriveConfig config;
        config.node = static_cast<std::uint8_t>(node);
        if (a) config.counts_per_turn = a->options_as<rig::Cia402Options>().counts_per_turn;
        config.initial_position = static_cast<std::int32_t>(std::lround(position));
        auto drive = std::make_unique<sim::SimCia402Drive>(config);
        sim::SimCia402Drive* raw = drive.get();
        return {std::move(drive), [raw] { return raw->position_counts(); }};
      },
      [] {
        SimOffer offer = drive_sim_offer(
            "cia402", "Simulated CANopen CiA 402 servo drives behind a simulated SLCAN adapter",
            "  avar sim cia402 --ids 5                   # prints /dev/pts/N\n  avar play SHOW.yaml --rig RIG.yaml "
            "--port /dev/pts/N   # a one-link rig: can: {...}, actuators with protocol: cia402, node: 5");
        offer.make = [](const SimValues& values) { return standalone_slcan(cia402_drive(), values); };
        return offer;
      }(),
  };
  return p;
}

}  // namespace avar::assembly
