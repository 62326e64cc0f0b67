#pragma once
// The Feetech SCS/STS bus driver over any ByteTransport. Per tick, in ONE transport write: a Sync
// Write of every driven servo's goal position (plus a Sync Write of torque off for servos
// released since the last tick) and, when read-back is configured, a Sync Read whose replies
// fill each channel's telemetry. The replies are awaited for at most reply_timeout in total;
// bad checksums, stray bytes and silent servos are counted in counters() and the decoder
// resynchronises on the next header, so one bad tick never shifts the next.

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "avar/firmware_iface/actuator_link.hpp"
#include "avar/firmware_iface/actuator_table.hpp"
#include "avar/firmware_iface/bus_exchange.hpp"
#include "avar/firmware_iface/byte_transport.hpp"
#include "avar/firmware_iface/feetech_bus_codec.hpp"
#include "avar/firmware_iface/feetech_codec.hpp"
#include "avar/firmware_iface/linear_calibration.hpp"

namespace avar::firmware_iface {

struct FeetechActuator {
  std::size_t channel = 0;  ///< rig channel index (position in the frames the loop sends)
  std::uint8_t id = 1;      ///< servo ID on the bus, 0..253
  /// Channel units -> position steps (0..4095 STS, 0..1023 SCS; 2048 / 512 = centre).
  LinearCalibration calibration{0, 1, 1024, 3072, false, 0};
  std::optional<double> speed_steps_per_s;          ///< Goal Speed register (absent: the servo's maximum)
  std::optional<double> acceleration_steps_per_s2;  ///< Acceleration register, 100 steps/s² units (absent: maximum)
};

/// What the per-tick Sync Read asks of each servo.
enum class FeetechReadback {
  none,      ///< write only
  position,  ///< 2 bytes at 56: present position (and the error byte's fault bits)
  full,      ///< 8 bytes at 56: position, speed, load, voltage, temperature (and fault bits)
};

struct FeetechLinkConfig {
  feetech::Series series = feetech::Series::sts;
  /// The bus rate the transport was opened at; used for describe() and link budgets only.
  int baud = 1'000'000;
  FeetechReadback readback = FeetechReadback::full;
  /// The servos' Response Level is 1 (the factory setting): start() then waits for each
  /// Write's status reply. With 0 only Read and Ping are answered.
  bool replies_to_writes = true;
  /// Longest a send() waits for its Sync Read replies, and a start() query for its reply.
  /// Replies that have already arrived are still taken after it (reads of 0 ms: at most 1 ms
  /// each on SerialTransport), never more bytes than were asked for.
  std::chrono::milliseconds reply_timeout{10};
  /// Plain Read retries per send for servos whose Sync Read reply was lost or corrupt.
  std::uint32_t retries = 1;
  /// Sends in a row without a reply from a servo before send() reports a timeout.
  std::uint32_t silent_exchanges = 10;
  /// While the port is gone, reopen it every this many sends.
  std::uint32_t reconnect_every = 10;
  std::vector<FeetechActuator> actuators;
};

class FeetechLink final : public ActuatorLink {
 public:
  /// Largest number of servos one Sync Write of 2-byte goals can carry.
  static constexpr std::size_t kMaxServos = 83;

  /// Sizes every buffer. Throws std::invalid_argument for no actuators, more than kMaxServos,
  /// an ID above 253 or an ID used twice. The transport is borrowed.
  FeetechLink(ByteTransport& transport, FeetechLinkConfig config);

  /// Pings every servo (a servo that does not answer within the reply timeout: timeout), sends
  /// speed and acceleration limits, sets each goal to the present position, and turns torque
  /// on. Not real-time.
  Status start() override;
  /// Sync Read of present position; servos that do not answer in time are left unknown (and
  /// the result is timeout). Not real-time.
  Status read_positions(std::span<double> frame, std::span<bool> known) override;
  /// One write (sync write of goals, plus the sync read request when read-back is on), then
  /// the replies, waiting at most reply_timeout, then at most `retries` plain reads for lost or
  /// corrupt replies. Corrupt and lost replies are counted and leave that servo's telemetry
  /// unknown for the tick; a servo silent for `silent_exchanges` sends in a row makes it return
  /// timeout. After an I/O error it returns io_error and reopens the port on later sends.
  Status send(std::span<const double> frame) noexcept override;
  /// Broadcast torque off (no reply). Real-time safe.
  Status release() noexcept override;
  void release_channel(std::size_t channel) noexcept override;
  std::uint64_t saturated_pulses() const noexcept override { return table_.saturated(); }
  const std::string& describe() const noexcept override { return description_; }
  void read_telemetry(std::span<ChannelTelemetry> out) const noexcept override;
  LinkCounters counters() const noexcept override { return bus_.counters(); }

  /// Bytes of the last send()'s write, for link-budget reports.
  std::size_t last_send_size() const noexcept { return last_send_size_; }
  /// Bytes the servos' replies to one send() take (all of them answering).
  std::size_t reply_bytes_per_tick() const noexcept;

 private:
  /// Writes a request and waits for the one reply of `data_length` bytes of the servo in
  /// `slot`; copies up to two of its bytes into `params`. bad_data when the servo refused it.
  Status query(std::size_t slot, std::span<const std::uint8_t> request, std::size_t data_length,
               std::span<std::uint8_t> params = {}) noexcept;
  /// Takes one status reply of `length` data bytes into the slot's telemetry.
  void take_telemetry(std::size_t slot, const BusReply& reply, std::uint8_t length) noexcept;
  Status write_register(std::size_t slot, std::uint8_t address, std::span<const std::uint8_t> data);
  std::uint8_t readback_length() const noexcept;

  ByteTransport& transport_;
  FeetechLinkConfig config_;
  std::string description_;
  ActuatorTable table_;
  FeetechBusCodec codec_;
  BusExchange bus_;
  std::vector<std::uint8_t> ids_;         ///< scratch: IDs of one packet
  std::vector<std::uint16_t> goals_;      ///< scratch: goal words of one packet
  std::vector<std::uint8_t> torque_off_;  ///< scratch: zeros for the torque-off packet
  std::vector<std::size_t> all_slots_;    ///< 0..n-1
  std::vector<std::uint8_t> packet_;      ///< the whole tick's bytes
  std::size_t last_send_size_ = 0;
};

}  // namespace avar::firmware_iface
