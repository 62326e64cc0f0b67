#pragma once
// Hobby servos on a PWM chip's own outputs, as a link (a Raspberry Pi's hardware PWM through
// sysfs): each actuator is one output, whose pulse width (µs, through the actuator's calibration)
// follows one channel, one pulse per period. start() claims every output with the period, sending
// nothing; send() writes the outputs whose pulse changed (to the nanosecond), switching them on
// the first time; a released channel's outputs are switched off (the servo goes limp), and
// release() switches every output off. Nothing reports back.

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "avar/firmware_iface/actuator_link.hpp"
#include "avar/firmware_iface/actuator_table.hpp"
#include "avar/firmware_iface/atomic_link_counters.hpp"
#include "avar/firmware_iface/linear_calibration.hpp"
#include "avar/firmware_iface/pwm_chip.hpp"

namespace avar::firmware_iface {

struct PwmOutput {
  std::size_t channel = 0;  ///< rig channel index
  unsigned pin = 0;         ///< the chip's output
  /// Channel units -> pulse width in µs.
  LinearCalibration calibration{0, 1, 1000, 2000, false, 0};
};

struct PwmLinkConfig {
  std::vector<PwmOutput> outputs;
  std::uint32_t frequency_hz = 50;  ///< pulses per second (hobby servos: 50)
  std::string description;          ///< "PWM link 'arm' on PWM chip /sys/class/pwm/pwmchip0"
};

class PwmLink final : public ActuatorLink {
 public:
  /// Throws std::invalid_argument for no outputs, an output used twice, a frequency outside 1 to
  /// 1000 Hz, or a pulse range longer than the period.
  PwmLink(std::shared_ptr<PwmChip> chip, PwmLinkConfig config);
  PwmLink(const PwmLink&) = delete;
  PwmLink& operator=(const PwmLink&) = delete;

  /// Claims every output with the period, each off until the first send. io_error (and
  /// start_problem) when the chip refuses an output.
  Status start() override;
  std::string start_problem() const override { return start_problem_; }
  Status read_positions(std::span<double> frame, std::span<bool> known) override;
  /// Writes each output whose pulse changed, every output on the first send; a released
  /// channel's outputs off. Real-time safe: a write or two per changed output.
  Status send(std::span<const double> frame) noexcept override;
  /// Every output off. Real-time safe.
  Status release() noexcept override;
  void release_channel(std::size_t channel) noexcept override { table_.release_channel(channel); }
  std::uint64_t saturated_pulses() const noexcept override { return table_.saturated(); }
  const std::string& describe() const noexcept override { return config_.description; }
  /// exchanges: send() calls; device_errors: changes the chip refused.
  LinkCounters counters() const noexcept override { return counters_.snapshot(); }

  std::uint32_t period_ns() const noexcept { return period_ns_; }

 private:
  std::shared_ptr<PwmChip> chip_;
  PwmLinkConfig config_;
  ActuatorTable table_;
  std::uint32_t period_ns_ = 0;
  std::vector<std::int64_t> written_;  ///< per output: the pulse (ns) last written, -2 off, -1 before the first send
  std::atomic<bool> all_released_{false};
  AtomicLinkCounters counters_;
  std::string start_problem_;
};

}  // namespace avar::firmware_iface
