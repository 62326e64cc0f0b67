#include "avar/firmware_iface/dmx_universe.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "avar/core/byte_order.hpp"

namespace avar::firmware_iface {
namespace {

constexpr std::size_t kDmxUniverseSlots = 512;

}  // namespace

DmxUniverse::DmxUniverse(std::vector<DmxActuator> actuators, std::size_t slot_count, std::size_t min_slots)
    : actuators_(std::move(actuators)), table_(actuators_) {
  if (actuators_.empty()) throw std::invalid_argument("a DMX link needs at least one actuator");
  std::array<bool, kDmxUniverseSlots + 1> used{};
  std::size_t highest = 0;
  for (const DmxActuator& a : actuators_) {
    const int last = a.address + (a.fine ? 1 : 0);
    if (a.address < 1 || last > static_cast<int>(kDmxUniverseSlots))
      throw std::invalid_argument("DMX address " + std::to_string(a.address) + (a.fine ? " (16-bit)" : "") +
                                  " does not fit in 1..512");
    for (int s = a.address; s <= last; ++s) {
      if (used[static_cast<std::size_t>(s)]) throw std::invalid_argument("DMX slot " + std::to_string(s) + " is used twice");
      used[static_cast<std::size_t>(s)] = true;
    }
    highest = std::max(highest, static_cast<std::size_t>(last));
  }
  if (slot_count > kDmxUniverseSlots || (slot_count != 0 && slot_count < highest))
    throw std::invalid_argument("DMX slot count " + std::to_string(slot_count) + " must cover slot " + std::to_string(highest) +
                                " and stay within 512");
  slots_.assign(std::min(std::max(slot_count == 0 ? highest : slot_count, min_slots), kDmxUniverseSlots), 0);
}

void DmxUniverse::fill(std::span<const double> frame) noexcept {
  for (std::size_t i = 0; i < actuators_.size(); ++i) {
    const DmxActuator& a = actuators_[i];
    long level = 0;
    if (!table_.released(i)) level = std::clamp(std::lround(table_.to_device(i, frame)), 0L, a.fine ? 65535L : 255L);
    const auto at = static_cast<std::size_t>(a.address - 1);
    if (a.fine) {
      put_u16_be(&slots_[at], static_cast<std::uint16_t>(level));
    } else {
      slots_[at] = static_cast<std::uint8_t>(level);
    }
  }
}

void DmxUniverse::zero_all() noexcept {
  for (const DmxActuator& a : actuators_) {
    slots_[static_cast<std::size_t>(a.address - 1)] = 0;
    if (a.fine) slots_[static_cast<std::size_t>(a.address)] = 0;
  }
}

}  // namespace avar::firmware_iface
