#pragma once
// What every driver keeps per actuator, whatever its protocol: the rig channel it follows, its
// calibration (with the count of saturated commands), whether it is released (fail-safe: no
// longer driven) and whether the device has been told so, and the latest telemetry of devices
// that report any. Indices are the driver's actuator order (its config's `actuators`).
//
// Threads: release_channel() and saturated() from any thread; everything else on the thread that
// calls the driver's send(). Everything but the constructor is real-time safe: no allocation,
// no exception.

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "avar/firmware_iface/actuator_link.hpp"
#include "avar/firmware_iface/linear_calibration.hpp"

namespace avar::firmware_iface {

class ActuatorTable {
 public:
  /// One entry per element of `actuators`, each of which has `channel` and `calibration`.
  template <class Actuators>
  explicit ActuatorTable(const Actuators& actuators) : ActuatorTable(actuators.size()) {
    for (std::size_t i = 0; i < actuators.size(); ++i) {
      channels_[i] = actuators[i].channel;
      calibrations_[i] = actuators[i].calibration;
    }
  }

  std::size_t size() const noexcept { return channels_.size(); }
  std::size_t channel(std::size_t i) const noexcept { return channels_[i]; }
  const LinearCalibration& calibration(std::size_t i) const noexcept { return calibrations_[i]; }

  /// The device value for actuator i's channel in `frame` (indexed by rig channel), saturated
  /// to its calibration's window; saturation is counted.
  double to_device(std::size_t i, std::span<const double> frame) noexcept;
  /// The channel value a device value of actuator i stands for.
  double to_channel(std::size_t i, double device_value) const noexcept { return calibrations_[i].to_channel(device_value); }
  /// Commands saturated since construction. Any thread.
  std::uint64_t saturated() const noexcept { return saturated_.load(std::memory_order_relaxed); }

  /// Releases the actuators of one rig channel (others are ignored). Any thread.
  void release_channel(std::size_t channel) noexcept;
  /// Releases every actuator and records that the device was told (one broadcast did it).
  void release_all_told() noexcept;
  bool released(std::size_t i) const noexcept { return released_[i].load(std::memory_order_relaxed); }
  /// Released, and the device not yet told to stop driving it.
  bool release_pending(std::size_t i) const noexcept { return released(i) && !told_[i]; }
  /// The device now knows actuator i is released (false: tell it again on the next send).
  void set_release_told(std::size_t i, bool told = true) noexcept { told_[i] = told; }

  /// Latest telemetry of actuator i, for the driver to refresh from a reply.
  ChannelTelemetry& telemetry(std::size_t i) noexcept { return telemetry_[i]; }
  /// Stale feedback is absent, not old: position, load and temperature become unknown (the
  /// fault bits stay as of the last reply).
  void forget_feedback(std::size_t i) noexcept;
  /// Copies each actuator's telemetry into out[its channel].
  void read_telemetry(std::span<ChannelTelemetry> out) const noexcept;

 private:
  explicit ActuatorTable(std::size_t n);

  std::vector<std::size_t> channels_;
  std::vector<LinearCalibration> calibrations_;
  std::unique_ptr<std::atomic<bool>[]> released_;
  std::unique_ptr<bool[]> told_;
  std::vector<ChannelTelemetry> telemetry_;
  std::atomic<std::uint64_t> saturated_{0};
};

}  // namespace avar::firmware_iface
