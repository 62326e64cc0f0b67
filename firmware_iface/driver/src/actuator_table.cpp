#include "avar/firmware_iface/actuator_table.hpp"

namespace avar::firmware_iface {

ActuatorTable::ActuatorTable(std::size_t n)
    : channels_(n),
      calibrations_(n),
      released_(std::make_unique<std::atomic<bool>[]>(n)),
      told_(std::make_unique<bool[]>(n)),
      telemetry_(n) {}

double ActuatorTable::to_device(std::size_t i, std::span<const double> frame) noexcept {
  bool clamped = false;
  const double value = calibrations_[i].to_device(frame[channels_[i]], &clamped);
  if (clamped) saturated_.fetch_add(1, std::memory_order_relaxed);
  return value;
}

void ActuatorTable::release_channel(std::size_t channel) noexcept {
  for (std::size_t i = 0; i < size(); ++i)
    if (channels_[i] == channel) released_[i].store(true, std::memory_order_relaxed);
}

void ActuatorTable::release_all_told() noexcept {
  for (std::size_t i = 0; i < size(); ++i) {
    released_[i].store(true, std::memory_order_relaxed);
    told_[i] = true;
  }
}

void ActuatorTable::forget_feedback(std::size_t i) noexcept {
  ChannelTelemetry& t = telemetry_[i];
  t.position = ChannelTelemetry::kUnknown;
  t.load = ChannelTelemetry::kUnknown;
  t.temperature_c = ChannelTelemetry::kUnknown;
}

void ActuatorTable::read_telemetry(std::span<ChannelTelemetry> out) const noexcept {
  for (std::size_t i = 0; i < size(); ++i) out[channels_[i]] = telemetry_[i];
}

}  // namespace avar::firmware_iface
