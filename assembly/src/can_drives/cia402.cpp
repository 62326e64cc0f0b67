// The registry entry of CANopen CiA 402 servo drives (cyclic synchronous position) on a CAN link.
#include <array>
#include <cmath>

#include "../setting_reading.hpp"
#include "avar/firmware_iface/cia402_drives.hpp"
#include "avar/sim/sim_cia402_drive.hpp"
#include "can_drive_entries.hpp"

namespace avar::assembly {
namespace {

constexpr std::array<std::string_view, 1> kCia402Keys{"counts_per_turn"};

double counts_per_turn_of(const rig::ActuatorSpec& a) {
  const ScalarValue* c = a.settings.find("counts_per_turn");
  if (!c)
    ScalarValue{"", false, "nothing", a.where}.fail(
        "expected counts_per_turn for the CiA 402 drive at node " + std::to_string(a.device_channel) +
        ": the position counts of one motor turn in the drive's user units (its encoder resolution, such as 131072 for 17 bits)");
  return static_cast<double>(integer_in(*c, "counts_per_turn", 1, 1LL << 30));
}

}  // namespace

const CanDriveProtocol& cia402_drive() {
  static const CanDriveProtocol p{
      "cia402",
      "CiA 402 drive",
      1,
      127,
      "counts",
      "any CANopen rate; 500000 and 1000000 are usual",
      [](int) { return true; },
      [] { return std::span<const std::string_view>(kCia402Keys); },
      [](const rig::ActuatorSpec& a) {
        // Targets are 32-bit counts.
        if (std::max(std::abs(a.calibration.device_low()), std::abs(a.calibration.device_high())) > 2147483647.0)
          a.settings.find("counts_per_turn")
              ->fail(
                  "the channel's range takes this drive beyond the 32-bit position range (±2147483647 counts); expected "
                  "fewer counts_per_turn or a smaller gear_ratio");
      },
      counts_per_turn_of,
      [](const rig::ActuatorSpec& a, const CanBusOptions&, std::vector<CanIdRange>& out) {
        const auto node = static_cast<std::uint32_t>(a.device_channel);
        out.push_back({0x000, 0x000, true});  // NMT, from the host to every node
        out.push_back({0x080, 0x080, true});  // SYNC
        for (std::uint32_t base :
             {0x080u, 0x180u, 0x200u, 0x280u, 0x300u, 0x380u, 0x400u, 0x480u, 0x500u, 0x580u, 0x600u, 0x700u})
          out.push_back({base + node, base + node, false});
      },
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
        if (a) config.counts_per_turn = counts_per_turn_of(*a);
        config.initial_position = static_cast<std::int32_t>(std::lround(position));
        auto drive = std::make_unique<sim::SimCia402Drive>(config);
        sim::SimCia402Drive* raw = drive.get();
        return {std::move(drive), [raw] { return raw->position_counts(); }};
      },
  };
  return p;
}

}  // namespace avar::assembly
