#pragma once
// A simulated I2C bus with PCA9685 boards on it: each write is applied to the addressed board's
// registers as the chip applies it (the shared codec's register file), and a test or the
// simulator reads each output's pulse. An address without a board does not acknowledge; a board
// can be told to stop acknowledging (a loose wire).

#include <cstdint>
#include <map>
#include <mutex>
#include <span>
#include <string>
#include <vector>

#include "avar/firmware_iface/i2c_bus.hpp"
#include "avar/firmware_iface/pca9685_codec.hpp"

namespace avar::sim {

class SimI2cBus final : public firmware_iface::I2cBus {
 public:
  SimI2cBus() = default;
  /// A PCA9685 at `address`, at its power-on state.
  void add_pca9685(std::uint8_t address);
  /// Whether the board at `address` acknowledges (true once added).
  void set_answering(std::uint8_t address, bool answering);

  Status write(std::uint8_t address, std::span<const std::uint8_t> bytes) noexcept override;
  /// A simulated board settles at once; the waits asked for are summed (settled_us).
  void settle(std::uint32_t us) override;
  std::uint64_t settled_us() const;
  const std::string& describe() const noexcept override { return description_; }

  /// The board's registers (a copy), and one output's pulse width in µs from its registers and
  /// its prescale at a 25 MHz clock (0 when off).
  firmware_iface::pca9685::Registers registers(std::uint8_t address) const;
  double pulse_us(std::uint8_t address, std::uint8_t output, std::uint32_t clock_hz = 25000000) const;
  /// Every write received, with its address (writes to absent boards too).
  std::vector<std::vector<std::uint8_t>> writes(std::uint8_t address) const;

 private:
  struct Board {
    firmware_iface::pca9685::Registers registers{};
    bool answering = true;
    std::vector<std::vector<std::uint8_t>> writes;
  };
  mutable std::mutex mutex_;
  std::map<std::uint8_t, Board> boards_;
  std::uint64_t settled_us_ = 0;
  std::string description_ = "simulated I2C bus";
};

}  // namespace avar::sim
