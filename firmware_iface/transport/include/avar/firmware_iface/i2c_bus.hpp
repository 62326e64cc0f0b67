#pragma once
// The I2C seam: write transactions to 7-bit addresses on one bus (/dev/i2c-1 on a Raspberry Pi
// header). open_i2c_bus() (linux_i2c_bus.hpp, avar::transport_i2c) opens a real bus through the
// kernel's i2c-dev; avar::sim::SimI2cBus is a simulated one with boards on it.
//
// Threads: one thread writes at a time (a link's send, or its start before the loop runs).

#include <cstdint>
#include <span>
#include <string>

#include "avar/core/status.hpp"

namespace avar::firmware_iface {

class I2cBus {
 public:
  virtual ~I2cBus() = default;
  /// One write transaction (start, address, the bytes, stop). io_error when the device does not
  /// acknowledge or the bus fails. Real-time safe in every implementation: one kernel call at most.
  virtual Status write(std::uint8_t address, std::span<const std::uint8_t> bytes) noexcept = 0;
  /// Waits `us` microseconds for a device on the bus to settle (a PCA9685's oscillator after
  /// waking). A real bus sleeps; a simulated one has nothing to wait for. Load-time only.
  virtual void settle(std::uint32_t us) = 0;
  /// "I2C bus /dev/i2c-1", "simulated I2C bus".
  virtual const std::string& describe() const noexcept = 0;
};

}  // namespace avar::firmware_iface
