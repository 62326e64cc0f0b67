#pragma once
// Hobby servos on a PCA9685 board over an I2C bus, as a link: each actuator is one of the board's
// 16 outputs, whose pulse width (µs, through the actuator's calibration) follows one channel.
// start() sets the board's period (sleep, prescale, outputs, wake, restart); send() writes the
// outputs whose pulse changed, one 5-byte transaction each; a released channel's outputs are
// switched fully off (the servo goes limp), and release() switches every output off at once.
// The bytes are the shared codec's (pca9685_codec.hpp), the same the device's player writes.
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
#include "avar/firmware_iface/i2c_bus.hpp"
#include "avar/firmware_iface/linear_calibration.hpp"

namespace avar::firmware_iface {

struct Pca9685Output {
  std::size_t channel = 0;  ///< rig channel index
  std::uint8_t output = 0;  ///< the board's output, 0..15
  /// Channel units -> pulse width in µs.
  LinearCalibration calibration{0, 1, 1000, 2000, false, 0};
};

struct Pca9685LinkConfig {
  std::vector<Pca9685Output> outputs;
  std::uint8_t address = 0x40;        ///< 7-bit I2C address
  std::uint32_t frequency_hz = 50;    ///< the pulses' rate (hobby servos: 50)
  std::uint32_t clock_hz = 25000000;  ///< the board's oscillator (a calibrated value, or EXTCLK's)
  bool totem_pole = true;             ///< the boards' outputs (open drain when false)
  std::string description;            ///< "PCA9685 link 'arm' at 0x40 on I2C bus /dev/i2c-1"
};

class Pca9685Link final : public ActuatorLink {
 public:
  /// Throws std::invalid_argument for no outputs, an output above 15 or used twice, an address
  /// outside 0x03..0x77, a frequency the prescale cannot reach (24 to 1526 Hz at 25 MHz).
  Pca9685Link(std::shared_ptr<I2cBus> bus, Pca9685LinkConfig config);
  Pca9685Link(const Pca9685Link&) = delete;
  Pca9685Link& operator=(const Pca9685Link&) = delete;

  /// The start-up sequence, every output off until the first send. io_error (and start_problem)
  /// when the board does not acknowledge.
  Status start() override;
  std::string start_problem() const override { return start_problem_; }
  Status read_positions(std::span<double> frame, std::span<bool> known) override;
  /// Writes each output whose pulse (in counts) changed, every output on the first send; a
  /// released channel's outputs fully off. Real-time safe: one ioctl per changed output.
  Status send(std::span<const double> frame) noexcept override;
  /// Every output fully off at once (ALL_LED). Real-time safe.
  Status release() noexcept override;
  void release_channel(std::size_t channel) noexcept override { table_.release_channel(channel); }
  std::uint64_t saturated_pulses() const noexcept override { return table_.saturated(); }
  const std::string& describe() const noexcept override { return config_.description; }
  /// exchanges: send() calls; bytes_sent: the bytes of acknowledged writes (without the address);
  /// device_errors: writes not acknowledged.
  LinkCounters counters() const noexcept override { return counters_.snapshot(); }

  std::uint8_t prescale() const noexcept { return prescale_; }
  /// Output writes done since construction (changes only). Any thread.
  std::uint64_t output_writes() const noexcept { return output_writes_.load(std::memory_order_relaxed); }

 private:
  Status write(const std::uint8_t* bytes, std::size_t length) noexcept;

  std::shared_ptr<I2cBus> bus_;
  Pca9685LinkConfig config_;
  ActuatorTable table_;
  std::uint8_t prescale_ = 0;
  std::vector<int> written_;  ///< per output: the counts last written (-2 off), -1 before the first send
  std::atomic<bool> all_released_{false};
  AtomicLinkCounters counters_;
  std::atomic<std::uint64_t> output_writes_{0};
  std::string start_problem_;
};

}  // namespace avar::firmware_iface
