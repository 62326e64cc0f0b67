#pragma once
// The DYNAMIXEL Protocol 2.0 driver (X-series): several servos on one half-duplex bus over any
// ByteTransport. Per send(): ONE Sync Write of every goal position, then (readback) ONE Sync Read
// whose replies refresh each servo's telemetry: position, load and temperature; a reply with the
// Alert bit makes the next exchange read Hardware Error Status, whose bits become DeviceFault
// flags (overheat, overload...). Bad CRCs and stray bytes are counted and skipped without losing
// sync; a missing reply costs at most one reply timeout per exchange and is retried a bounded
// number of times (BusExchange); a servo whose reply is still missing has its position, load and
// temperature unknown until it answers again (stale feedback is absent); a servo that misses
// `silent_exchanges` exchanges in a row makes send() report a timeout (the controller's watchdog
// fault). An I/O error (port gone) makes send() report
// io_error and try to reopen the port on later sends, re-enabling torque once it is back.
//
// Threads: send() and read_telemetry() run on one thread (the link's I/O thread); counters() may
// be read from any. send() allocates nothing and throws nothing; it waits for replies, bounded
// by the reply timeout, so it belongs on an I/O thread (control::ThreadedLink), never the tick.

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "avar/firmware_iface/actuator_link.hpp"
#include "avar/firmware_iface/actuator_table.hpp"
#include "avar/firmware_iface/bus_exchange.hpp"
#include "avar/firmware_iface/byte_transport.hpp"
#include "avar/firmware_iface/dynamixel_bus_codec.hpp"
#include "avar/firmware_iface/linear_calibration.hpp"

namespace avar::firmware_iface {

struct DynamixelActuator {
  std::size_t channel = 0;                   ///< rig channel index
  std::uint8_t id = 1;                       ///< servo ID, 0..252
  LinearCalibration calibration;             ///< channel units -> position pulses (0.088° each, 0..4095 per turn)
  std::optional<double> speed_limit;         ///< device profile velocity, channel units/s
  std::optional<double> acceleration_limit;  ///< device profile acceleration, channel units/s²
};

enum class DynamixelReadback {
  none,      ///< write only: the fastest bus, no telemetry
  position,  ///< Present Position (4 bytes per servo)
  full,      ///< Present Load .. Present Temperature (addresses 126..146, 21 bytes per servo)
};

struct DynamixelLinkConfig {
  std::vector<DynamixelActuator> actuators;
  DynamixelReadback readback = DynamixelReadback::full;
  /// Longest wait for the replies of one exchange (a silent servo costs this once per send).
  std::chrono::milliseconds reply_timeout{10};
  /// Plain Read retries per exchange for servos whose Sync Read reply was lost or corrupt.
  std::uint32_t retries = 1;
  /// Exchanges in a row without a reply from a servo before send() reports a timeout.
  std::uint32_t silent_exchanges = 10;
  /// While the port is gone, reopen it every this many sends.
  std::uint32_t reconnect_every = 10;
};

class DynamixelLink final : public ActuatorLink {
 public:
  /// Sizes every buffer. Throws std::invalid_argument for an ID out of range or used twice.
  /// The transport is borrowed.
  DynamixelLink(ByteTransport& transport, DynamixelLinkConfig config);

  /// Pings every servo (a missing one is a timeout), reads its Status Return Level (readback
  /// needs 1 or 2: otherwise out_of_range, see start_problem()) and Return Delay Time (added to
  /// the reply timeout), writes profile velocity / acceleration and enables torque.
  Status start() override;
  std::string start_problem() const override { return start_problem_; }

  /// Reads Present Position of each servo.
  Status read_positions(std::span<double> frame, std::span<bool> known) override;
  Status send(std::span<const double> frame) noexcept override;
  /// Torque off on every servo (one Sync Write of Torque Enable = 0).
  Status release() noexcept override;
  /// The servo stops being driven: torque off on the next send, and no more goal positions.
  void release_channel(std::size_t channel) noexcept override;
  std::uint64_t saturated_pulses() const noexcept override { return table_.saturated(); }
  const std::string& describe() const noexcept override { return description_; }
  void read_telemetry(std::span<ChannelTelemetry> out) const noexcept override;
  LinkCounters counters() const noexcept override;

  /// Bytes written and read by the last send(), for link-budget reports.
  std::size_t last_exchange_bytes() const noexcept { return bus_.exchange_bytes(); }

 private:
  struct Servo {
    std::uint8_t id = 0;
    std::size_t actuator = 0;
    bool read_hardware_error = false;      ///< an Alert was seen: read address 70 next exchange
    std::uint8_t status_return_level = 2;  ///< 0: Ping only, 1: + Read, 2: every instruction
  };
  /// Sends a request and waits for the status packet of `servo` with at least `params`
  /// parameter bytes; *value gets the first one (params 1) or four (params 4) of them.
  Status query(const Servo& servo, std::span<const std::uint8_t> request, std::size_t params,
               std::int32_t* value = nullptr) noexcept;
  /// A write that the servo answers when its Status Return Level says so.
  Status write_to(const Servo& servo, std::span<const std::uint8_t> request) noexcept;
  void take_reply(Servo& servo, const BusReply& reply) noexcept;
  Status enable_torque() noexcept;
  Status exchange_telemetry() noexcept;

  ByteTransport& transport_;
  DynamixelLinkConfig config_;
  ActuatorTable table_;
  DynamixelBusCodec codec_;
  BusExchange bus_;
  std::vector<Servo> servos_;         ///< sorted by ID
  std::vector<std::uint8_t> ids_;     ///< scratch: IDs of one instruction
  std::vector<std::int32_t> values_;  ///< scratch: values of one Sync Write
  std::vector<std::size_t> asked_;    ///< scratch: actuators of one Sync Read
  std::vector<std::uint8_t> packet_;  ///< outgoing bytes
  std::uint16_t read_address_ = 0, read_length_ = 0;
  std::string description_;
  std::string start_problem_;
};

}  // namespace avar::firmware_iface
