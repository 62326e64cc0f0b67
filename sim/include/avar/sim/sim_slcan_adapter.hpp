#pragma once
// A simulated SLCAN (Lawicel) USB-CAN adapter, CANable-like (../shared/protocols/slcan.md), with
// a simulated CAN bus behind it in instant timing: a frame the host transmits reaches the
// bus's nodes at once and their replies come back as received-frame lines at once; the bus's
// time moves only with advance(). Serve it on a pseudo-terminal (PtyDeviceHost) or an
// in-memory wire (SimWire) and drive it with SlcanTransport.
//
// Behaviour (slcan.md §4): every command ends with CR; the answer is CR (ok) or BEL (refused).
// `t/T/r/R` are refused while closed, in listen-only mode and while bus-off; `S/s` while open;
// ids, DLC and the number of hex pairs are checked. `V`, `N`, `F` (Lawicel flag layout, cleared
// on reading), `Zn`, `O`, `L`, `C` are answered as the note says (`C` while closed: BEL, as
// Lawicel). Transmits are acknowledged with `z`/`Z` + CR when transmit_acks is set, else with
// a bare CR. Nothing is echoed; nothing unsolicited is sent but received frames (with a 4-digit
// millisecond timestamp after `Z1`) and, when linux_error_lines is set, the Linux driver's
// state (`s`) and error (`e`) lines for the bus's error frames. An adapter set to a bitrate
// other than the bus's hears nothing and its transmits end in protocol errors.
//
// Not thread-safe: a host (PtyDeviceHost, SimWire) serialises calls.

#include <cstdint>
#include <deque>
#include <string>
#include <string_view>
#include <vector>

#include "avar/sim/byte_device.hpp"
#include "avar/sim/sim_can_bus.hpp"

namespace avar::sim {

struct SimSlcanConfig {
  int bus_bitrate = 1'000'000;    ///< bit/s of the bus behind the adapter
  int initial_code = 8;           ///< the `Sn` code the adapter powers up with
  bool transmit_acks = false;     ///< answer t/T/r/R with `z`/`Z` + CR (Lawicel) instead of CR (CANable)
  bool linux_error_lines = true;  ///< report the bus's error frames as `s`/`e` lines
  std::string version = "V1013";  ///< the answer to `V`
  std::string serial = "NA123";   ///< the answer to `N`
  double idle_step_s = 1e-3;      ///< the bus's idle step (its nodes' time resolution between frames)
};

class SimSlcanAdapter final : public ByteDevice {
 public:
  /// nodes: borrowed simulated CAN devices on the bus (null entries ignored).
  explicit SimSlcanAdapter(SimSlcanConfig config = {}, const std::vector<CanNode*>& nodes = {});

  void receive(std::span<const std::uint8_t> bytes) override;
  std::size_t take_replies(std::span<std::uint8_t> out) override;
  /// Advances the bus (and its nodes) by dt_s and sends the host what they put on the bus.
  void advance(double dt_s) override;
  std::uint64_t bytes_received() const override { return bytes_received_; }

  /// The bus behind the adapter: add and detach nodes, inject faults, read the load. After
  /// injecting, the next receive() or advance() reports what the adapter saw.
  SimCanBus& bus() noexcept { return bus_; }
  /// Sends the host the lines of whatever the bus holds for it now (after a fault injection).
  void flush_bus();

  bool is_open() const noexcept { return open_; }
  bool listen_only() const noexcept { return listen_only_; }
  /// The `Sn` code set (-1 after a custom `s` timing).
  int bitrate_code() const noexcept { return code_; }
  bool timestamps() const noexcept { return timestamps_; }
  /// Commands answered with BEL, and frames the host had transmitted onto the bus.
  std::uint64_t refused() const noexcept { return refused_; }
  std::uint64_t transmitted() const noexcept { return transmitted_; }

 private:
  void command(std::span<const std::uint8_t> line);
  void transmit(std::span<const std::uint8_t> line);
  bool bitrate_matches() const noexcept;
  void reply(std::string_view text);
  void ok() { reply("\r"); }
  void bell();
  void set_open(bool open, bool listen_only);

  SimSlcanConfig config_;
  SimCanBus bus_;
  bool open_ = false;
  bool listen_only_ = false;
  bool timestamps_ = false;
  int code_;
  std::uint8_t flags_ = 0;  ///< Lawicel status flags latched since the last `F`
  std::vector<std::uint8_t> line_;
  bool line_too_long_ = false;
  std::deque<std::uint8_t> replies_;
  std::uint64_t bytes_received_ = 0;
  std::uint64_t refused_ = 0;
  std::uint64_t transmitted_ = 0;
  std::uint64_t overruns_seen_ = 0;
};

}  // namespace avar::sim
