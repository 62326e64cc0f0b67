#pragma once
// The simulated CAN link of a rig: the rig's drives, simulated, on the bus behind a simulated
// SLCAN adapter, served as one byte device (a simulated `can` link runs the real SLCAN driver
// against it on a pseudo-terminal). Tests reach the drives and the bus through it, under their
// host's lock (FigureLinks::with_simulated). Not thread-safe, as every ByteDevice.

#include <vector>

#include "avar/assembly/can_drive.hpp"
#include "avar/rig/rig.hpp"
#include "avar/sim/byte_device.hpp"
#include "avar/sim/sim_slcan_adapter.hpp"

namespace avar::assembly {

class SimulatedCanBus final : public sim::ByteDevice {
 public:
  /// The drives of link `link` of a validated rig, each at its actuator's rest pose.
  SimulatedCanBus(const rig::Rig& rig, std::size_t link) : SimulatedCanBus(rig, link, can_bus_options(rig, link)) {}
  void receive(std::span<const std::uint8_t> bytes) override { adapter_.receive(bytes); }
  std::size_t take_replies(std::span<std::uint8_t> out) override { return adapter_.take_replies(out); }
  void advance(double dt_s) override { adapter_.advance(dt_s); }
  std::uint64_t bytes_received() const override { return adapter_.bytes_received(); }

  /// The drive of the i-th actuator on the link (rig order), and its true position in its own unit.
  sim::CanNode& drive(std::size_t i) { return *drives_[i].node; }
  double device_position(std::size_t i) const { return drives_[i].device_position(); }
  sim::SimSlcanAdapter& adapter() { return adapter_; }

 private:
  SimulatedCanBus(const rig::Rig& rig, std::size_t link, const CanBusOptions& bus)
      : drives_(simulated_drives(rig, link, bus)), adapter_(sim::SimSlcanConfig{.bus_bitrate = bus.bitrate}, nodes()) {}
  static std::vector<SimulatedDrive> simulated_drives(const rig::Rig& rig, std::size_t link, const CanBusOptions& bus) {
    std::vector<SimulatedDrive> drives;
    for (const rig::ActuatorSpec& a : rig.actuators_on(rig::LinkIndex{link})) {
      const double rest = a.calibration.to_device(rig.channel(a.channel).rest);
      drives.push_back(can_drive_of(a).make_simulated(&a, static_cast<std::uint32_t>(a.device_channel), rest, bus));
    }
    return drives;
  }
  std::vector<sim::CanNode*> nodes() const {
    std::vector<sim::CanNode*> out;
    for (const SimulatedDrive& d : drives_) out.push_back(d.node.get());
    return out;
  }

  std::vector<SimulatedDrive> drives_;  ///< before the adapter: its bus borrows them
  sim::SimSlcanAdapter adapter_;
};

}  // namespace avar::assembly
