#pragma once
// The Pololu Maestro driver: hobby servos on a Maestro, over any ByteTransport. Per tick it sends
// one "Set Multiple Targets" packet per run of consecutive device channels (one "Set Target" per
// channel on a Micro Maestro, which lacks that command), all in a single write.

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "avar/firmware_iface/actuator_link.hpp"
#include "avar/firmware_iface/actuator_table.hpp"
#include "avar/firmware_iface/byte_transport.hpp"
#include "avar/firmware_iface/maestro_actuators.hpp"
#include "avar/firmware_iface/maestro_codec.hpp"
#include "avar/firmware_iface/reconnector.hpp"

namespace avar::firmware_iface {

struct MaestroLinkConfig {
  maestro::Framing framing;
  int channel_count = 24;    ///< 6 = Micro Maestro (no Set Multiple Targets)
  bool baud_detect = false;  ///< send 0xAA first so a device in auto-baud mode locks on
  std::chrono::milliseconds reply_timeout{200};
  std::vector<MaestroActuator> actuators;
};

class MaestroLink final : public ActuatorLink {
 public:
  /// Plans the per-tick packets and sizes every buffer. Throws std::invalid_argument for a
  /// device channel out of range or used twice. The transport is borrowed.
  MaestroLink(ByteTransport& transport, MaestroLinkConfig config);

  /// Sends the baud-detection byte if asked, reads and clears the error register (a device
  /// that does not answer within the reply timeout is a timeout), and sends speed and
  /// acceleration limits.
  Status start() override;
  /// Get Position per actuator: the pulse the Maestro outputs now, mapped back to channel
  /// units. A channel that outputs no pulse (0, e.g. after power-up) is left unknown.
  Status read_positions(std::span<double> frame, std::span<bool> known) override;
  Status send(std::span<const double> frame) noexcept override;
  Status release() noexcept override;
  void release_channel(std::size_t channel) noexcept override;
  std::uint64_t saturated_pulses() const noexcept override { return table_.saturated(); }
  const std::string& describe() const noexcept override { return description_; }
  /// Only reconnects: the device does not answer every tick.
  LinkCounters counters() const noexcept override { return reconnector_.counters(); }

  /// Reads (and so clears) the device's error register.
  Status read_errors(std::uint16_t& errors);
  /// Bytes of the last send(), for link-budget reports.
  std::size_t last_send_size() const noexcept { return last_send_size_; }

 private:
  struct Run {
    std::uint8_t first_channel;
    std::size_t first_slot;  ///< index into slots_ (sorted by device channel)
    std::size_t count;
  };
  Status query(std::span<const std::uint8_t> request, std::span<std::uint8_t> reply);
  /// Encodes targets_ into one buffer and writes it; after the port came back (a Maestro that
  /// was unplugged restarts with its saved settings), first redoes what start() told it.
  Status write_targets() noexcept;
  /// The baud-detect byte, where configured.
  Status send_baud_detect() noexcept;
  /// Each actuator's speed and acceleration limits.
  Status send_limits() noexcept;

  ByteTransport& transport_;
  MaestroLinkConfig config_;
  std::vector<std::size_t> slots_;  ///< actuator indices sorted by device channel
  std::vector<Run> runs_;
  ActuatorTable table_;
  std::vector<std::uint16_t> targets_;  ///< quarter-µs per slot, rebuilt each send
  std::vector<std::uint8_t> packet_;    ///< the whole tick's bytes
  std::size_t last_send_size_ = 0;
  std::string description_;
  Reconnector reconnector_;  ///< reopens the port after an I/O error
};

}  // namespace avar::firmware_iface
