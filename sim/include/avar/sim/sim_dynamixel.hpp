#pragma once
// Simulated DYNAMIXEL X-series servos on one Protocol 2.0 bus (../shared/protocols/dynamixel-2.md).
// Decodes exactly the packets the real servos accept, answers as they do (status packets with
// the processing error and alert bits, Status Return Level honoured, broadcast rules), keeps a
// control table per servo, and moves each servo toward its goal (position mode, profile
// velocity, lag, load, and a temperature that rises with load until the overheating shutdown).
// Not thread-safe: a host (PtyDeviceHost) serialises calls.

#include <array>
#include <cstdint>
#include <deque>
#include <vector>

#include "avar/sim/byte_device.hpp"
#include "avar/sim/smart_servo_model.hpp"

namespace avar::sim {

struct SimDynamixelServo {
  std::uint8_t id = 1;
  std::uint16_t model_number = 1020;  ///< XM430-W350
  std::uint8_t firmware = 45;
  std::int32_t initial_position = 2048;  ///< pulses (0.088° each)
  double max_speed_pulses_per_s = 3000;  ///< no-load speed (~46 rev/min)
  double max_acceleration_pulses_per_s2 = 60'000;  ///< the motor's own limit (top speed in 50 ms)
  double time_constant_s = 0.02;
  double ambient_c = 25;
  double heating_c_per_s_at_full_load = 2;  ///< temperature rise rate at 100 % load
  double cooling_per_s = 0.01;              ///< fraction of the excess over ambient lost per second
};

struct SimDynamixelConfig {
  std::vector<SimDynamixelServo> servos;
  std::size_t log_limit = 0;  ///< keep up to this many decoded instruction packets
};

/// One decoded instruction, as the bus saw it.
struct DynamixelCommand {
  std::uint8_t id = 0;
  std::uint8_t instruction = 0;
  std::vector<std::uint8_t> params;
};

class SimDynamixel final : public ByteDevice {
 public:
  explicit SimDynamixel(SimDynamixelConfig config);

  void receive(std::span<const std::uint8_t> bytes) override;
  std::size_t take_replies(std::span<std::uint8_t> out) override;
  void advance(double dt_s) override;
  std::uint64_t bytes_received() const override { return bytes_received_; }

  /// Control-table access for tests and the simulator's own reports (servo by index).
  std::uint8_t read_u8(std::size_t servo, std::uint16_t address) const { return servos_[servo].table[address]; }
  std::int32_t read_i32(std::size_t servo, std::uint16_t address) const;
  double temperature_c(std::size_t servo) const { return servos_[servo].model.temperature_c(); }
  /// A test warming a servo: sets its temperature; it heats and cools from there.
  void set_temperature_c(std::size_t servo, double celsius) { servos_[servo].model.set_temperature_c(celsius); }
  /// Sets the load a servo's horn holds (a heavy prop), fraction of rated torque.
  void set_external_load(std::size_t servo, double load) { servos_[servo].model.set_external_load(load); }
  /// Present position in pulses (the model's exact value; the table holds it rounded).
  double position(std::size_t servo) const { return servos_[servo].model.position(); }
  std::uint64_t crc_errors() const { return crc_errors_; }
  const std::deque<DynamixelCommand>& log() const { return log_; }

 private:
  static constexpr std::size_t kTableSize = 256;
  struct Servo {
    SimDynamixelServo spec;
    std::array<std::uint8_t, kTableSize> table{};
    SmartServoModel model;
  };

  void handle(std::uint8_t id, std::uint8_t instruction, std::span<const std::uint8_t> params);
  void reply(const Servo& s, std::uint8_t error, std::span<const std::uint8_t> params);
  /// Writes data at address after the real servo's checks; returns the processing error (0 ok).
  std::uint8_t write(Servo& s, std::uint16_t address, std::span<const std::uint8_t> data);
  Servo* find(std::uint8_t id);
  void write_i32(Servo& s, std::uint16_t address, std::int32_t v);
  void write_u16(Servo& s, std::uint16_t address, std::uint16_t v);
  std::uint8_t status_error(const Servo& s, std::uint8_t processing) const;

  SimDynamixelConfig config_;
  std::vector<Servo> servos_;
  std::vector<std::uint8_t> input_;
  std::vector<std::uint8_t> scratch_;
  std::deque<std::uint8_t> replies_;
  std::deque<DynamixelCommand> log_;
  std::uint64_t bytes_received_ = 0;
  std::uint64_t crc_errors_ = 0;
};

}  // namespace avar::sim
