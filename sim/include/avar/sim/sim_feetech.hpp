#pragma once
// Simulated Feetech STS or SCS servos on one half-duplex bus (../shared/protocols/feetech-sts.md).
// Decodes exactly the packets the servos accept and answers as they do: a status packet per
// non-broadcast instruction (Response Level 1) or only to Read and Ping (level 0), none to a
// broadcast; each servo of a Sync Read answers in the order listed. Keeps a control table per
// servo in the series' byte order, and moves each servo toward its goal position (goal speed and
// acceleration limits, a first-order lag and a deadband: SmartServoModel) with a load that rises
// with acceleration, speed and an external load, and a temperature that rises with load until
// the overheat protection turns the torque off (the Status bit holds until 5 °C below the limit).
//
// Behaviour the notes leave open, as modelled here:
//  - Error replies use DYNAMIXEL Protocol 1.0 bits (see feetech::ErrorBit): a bad checksum is
//    answered with kErrorChecksum by the addressed servo; an unknown instruction with
//    kErrorInstruction; a Write outside the table, to a read-only register, of a goal outside
//    the position limits or of a torque-enable value other than 0, 1, 2 or 128 with kErrorRange
//    (and nothing is written). The Status register's bits are or-ed into every reply.
//  - The Lock register only decides persistence on the real servo; EEPROM writes apply here
//    either way.
//  - Sync Write blocks that fail those checks are dropped silently (no replies to broadcasts).
// Units: positions in steps, speeds in steps/s, time in seconds. Not thread-safe: a host
// (PtyDeviceHost) serialises calls.

#include <array>
#include <cstdint>
#include <deque>
#include <vector>

#include "avar/firmware_iface/feetech_codec.hpp"
#include "avar/sim/byte_device.hpp"
#include "avar/sim/smart_servo_model.hpp"

namespace avar::sim {

struct SimFeetechServo {
  std::uint8_t id = 1;
  double initial_position = -1;        ///< steps; < 0 = the centre (2048 STS, 512 SCS)
  double max_speed_steps_per_s = 3400; ///< no-load top speed (STS3215: ~3400 steps/s)
  double max_acceleration_steps_per_s2 = 68000;  ///< the motor's own limit (top speed in 50 ms)
  double time_constant_s = 0.02;
  double deadband_steps = 1;
  double external_load = 0;            ///< constant load the horn holds, fraction of rated torque
  double ambient_c = 25;
  double heating_c_per_s_at_full_load = 2;  ///< temperature rise rate at 100 % load
  double cooling_per_s = 0.01;              ///< fraction of the excess over ambient lost per second
  std::uint8_t max_temperature_c = 70;
  std::uint8_t voltage_decivolts = 120;
};

struct SimFeetechConfig {
  firmware_iface::feetech::Series series = firmware_iface::feetech::Series::sts;
  int baud = 1'000'000;  ///< the line's rate; sets the Baud Rate register and wire_time()
  std::vector<SimFeetechServo> servos;
  std::size_t log_limit = 0;  ///< keep up to this many decoded instruction packets
};

/// One decoded instruction, as the bus saw it.
struct FeetechCommand {
  std::uint8_t id = 0;
  std::uint8_t instruction = 0;
  std::vector<std::uint8_t> params;
};

class SimFeetech final : public ByteDevice {
 public:
  static constexpr std::size_t kTableSize = 71;  ///< addresses 0..70 (up to Present Current)

  /// Throws std::invalid_argument for a duplicate or out-of-range ID, or a baud rate the Baud
  /// Rate register cannot hold (FTServo table: 1 M, 500 k, 250 k, 128 k, 115 200, 76 800,
  /// 57 600, 38 400, 19 200, 14 400, 9600, 4800).
  explicit SimFeetech(SimFeetechConfig config);

  void receive(std::span<const std::uint8_t> bytes) override;
  std::size_t take_replies(std::span<std::uint8_t> out) override;
  /// Moves every servo dt_s seconds forward (in sub-steps of at most 1 ms).
  void advance(double dt_s) override;
  std::uint64_t bytes_received() const override { return bytes_received_; }

  /// Baud Rate register value for a rate, or -1 when the servo cannot do it.
  static int baud_code(int baud) noexcept;

  // Inspection (servo by index in the config).
  std::uint8_t read_u8(std::size_t servo, std::uint8_t address) const { return servos_[servo].table[address]; }
  /// A two-byte register in the series' byte order, raw (sign-magnitude not undone).
  std::uint16_t read_word(std::size_t servo, std::uint8_t address) const;
  /// Where the horn is, steps (the model's exact value; the table holds it rounded).
  double position(std::size_t servo) const;
  double temperature_c(std::size_t servo) const { return servos_[servo].model.temperature_c(); }
  double load(std::size_t servo) const { return servos_[servo].model.load(); }
  /// Sets the load the horn holds (a test pressing on the arm), fraction of rated torque.
  void set_external_load(std::size_t servo, double load) { servos_[servo].model.set_external_load(load); }
  /// Seconds a servo waits before answering (Return Delay register, 2 µs per unit).
  double reply_delay_s(std::size_t servo) const { return servos_[servo].table[firmware_iface::feetech::kReturnDelay] * 2e-6; }
  /// Seconds `bytes` take on this bus at its baud rate (8N1).
  double wire_time(std::size_t bytes) const;
  std::uint64_t checksum_errors() const { return checksum_errors_; }
  const std::deque<FeetechCommand>& log() const { return log_; }
  const SimFeetechConfig& config() const { return config_; }

 private:
  struct Servo {
    SimFeetechServo spec;
    std::array<std::uint8_t, kTableSize> table{};
    SmartServoModel model;
    bool pending = false;  ///< a Reg Write waits for Action
    std::uint8_t pending_address = 0;
    std::vector<std::uint8_t> pending_data;
  };

  void handle(std::uint8_t id, std::uint8_t instruction, std::span<const std::uint8_t> params);
  void reply(const Servo& s, std::uint8_t error, std::span<const std::uint8_t> params);
  /// Writes data at address after the servo's checks; returns the error bits (0 = written).
  std::uint8_t write(Servo& s, std::uint8_t address, std::span<const std::uint8_t> data);
  Servo* find(std::uint8_t id);
  void put_word(Servo& s, std::uint8_t address, std::uint16_t v);
  void step(Servo& s, double dt_s);

  SimFeetechConfig config_;
  std::vector<Servo> servos_;
  std::vector<std::uint8_t> input_;
  std::deque<std::uint8_t> replies_;
  std::deque<FeetechCommand> log_;
  std::uint64_t bytes_received_ = 0;
  std::uint64_t checksum_errors_ = 0;
};

}  // namespace avar::sim
