#pragma once
// One DMX512 universe of actuators, whatever carries it (an ENTTEC widget on USB, Art-Net or
// sACN on the network): 8-bit actuators on one slot, 16-bit ones on a coarse slot (high byte) at
// their address and a fine slot (low byte) at address + 1. Turns a frame of channel values into
// slot levels through each actuator's calibration, saturating to 0..255 (0..65535 fine).
//
// Threads: release_channel() and saturated() from any thread; fill() and release_all() on the
// thread that sends. Everything but the constructor is real-time safe.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "avar/firmware_iface/actuator_table.hpp"
#include "avar/firmware_iface/linear_calibration.hpp"

namespace avar::firmware_iface {

struct DmxActuator {
  std::size_t channel = 0;  ///< rig channel index
  int address = 1;          ///< DMX slot, 1..512 (1..511 when fine)
  bool fine = false;        ///< 16-bit: address = coarse (high byte), address + 1 = fine (low byte)
  /// Channel units -> DMX level: 0..255, or 0..65535 when fine.
  LinearCalibration calibration{0, 1, 0, 255, false, 0};
};

class DmxUniverse {
 public:
  /// `slot_count`: slots the universe holds, 0 = up to the highest slot an actuator uses;
  /// at least `min_slots`. Throws std::invalid_argument for no actuators, an address outside
  /// 1..512 (511 for fine), two actuators sharing a slot, or a slot_count that leaves an
  /// actuator out or exceeds 512.
  DmxUniverse(std::vector<DmxActuator> actuators, std::size_t slot_count, std::size_t min_slots);

  /// Sets every actuator's slots from `frame` (indexed by rig channel); released ones go to 0.
  void fill(std::span<const double> frame) noexcept;
  /// Every actuator's slots to level 0 (DMX has no "off").
  void zero_all() noexcept;
  void release_channel(std::size_t channel) noexcept { table_.release_channel(channel); }
  std::uint64_t saturated() const noexcept { return table_.saturated(); }

  /// Slot 1 at index 0.
  std::span<const std::uint8_t> slots() const noexcept { return slots_; }
  const std::vector<DmxActuator>& actuators() const noexcept { return actuators_; }

 private:
  std::vector<DmxActuator> actuators_;
  ActuatorTable table_;
  std::vector<std::uint8_t> slots_;
};

}  // namespace avar::firmware_iface
