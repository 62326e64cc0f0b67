#pragma once
// Digital outputs on a GPIO chip as a link: each actuator is one output line (a relay, a valve,
// an LED) that follows one channel, on (logical 1) while the channel's value is at or above the
// middle of its calibration's range, off otherwise. A line is set only when its value changes.
// Nothing reports back: read_positions() and read_telemetry() leave everything untouched.

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "avar/firmware_iface/actuator_link.hpp"
#include "avar/firmware_iface/actuator_table.hpp"
#include "avar/firmware_iface/atomic_link_counters.hpp"
#include "avar/firmware_iface/gpio_chip.hpp"
#include "avar/firmware_iface/linear_calibration.hpp"

namespace avar::firmware_iface {

struct GpioOutput {
  std::size_t channel = 0;  ///< rig channel index
  unsigned line = 0;        ///< the chip's line offset
  bool active_low = false;  ///< on drives the line low
  /// Channel units -> 0 (off) .. 1 (on); on from 0.5 up.
  LinearCalibration calibration{0, 1, 0, 1, false, 0};
  bool initial = false;  ///< the value the line is requested with (the channel's rest)
};

struct GpioLinkConfig {
  std::vector<GpioOutput> outputs;
  std::string description;  ///< "GPIO link 'props' on GPIO chip 'gpiochip0' (...)"
};

class GpioLink final : public ActuatorLink {
 public:
  /// Requests every output line of `chip` (shared: the rig's digital inputs may use the same
  /// chip) at its initial value. Throws std::invalid_argument for no outputs or a line used
  /// twice, std::runtime_error naming the chip and line when a request fails.
  GpioLink(std::shared_ptr<GpioChip> chip, GpioLinkConfig config);
  /// Gives the lines back (the kernel keeps an output's last value until someone else drives it).
  ~GpioLink() override;
  GpioLink(const GpioLink&) = delete;
  GpioLink& operator=(const GpioLink&) = delete;

  /// Nothing to prepare: the lines were requested by the constructor.
  Status start() override { return Status::ok; }
  Status read_positions(std::span<double> frame, std::span<bool> known) override;
  /// Sets each line whose value changed (and every line on the first send); a released line is
  /// driven off. Real-time safe: one ioctl per changed line. io_error when a set fails.
  Status send(std::span<const double> frame) noexcept override;
  /// Drives every line off at once, and keeps it off. Real-time safe.
  Status release() noexcept override;
  /// From the next send on, the channel's lines are driven off (a de-energised relay).
  void release_channel(std::size_t channel) noexcept override { table_.release_channel(channel); }
  std::uint64_t saturated_pulses() const noexcept override { return table_.saturated(); }
  const std::string& describe() const noexcept override { return config_.description; }
  /// exchanges: send() calls; device_errors: failed sets.
  LinkCounters counters() const noexcept override { return counters_.snapshot(); }

  /// Line sets done since construction (changes only). Any thread.
  std::uint64_t line_sets() const noexcept { return line_sets_.load(std::memory_order_relaxed); }

 private:
  std::shared_ptr<GpioChip> chip_;
  GpioLinkConfig config_;
  ActuatorTable table_;
  std::vector<signed char> driven_;  ///< per output: the value last set, -1 before the first send
  std::atomic<bool> all_released_{false};
  AtomicLinkCounters counters_;
  std::atomic<std::uint64_t> line_sets_{0};
};

}  // namespace avar::firmware_iface
