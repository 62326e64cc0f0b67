#pragma once
// The live timecode sources: Art-Net timecode over UDP and MIDI Time Code from an ALSA sequencer
// port. Each receives on a thread of its own, decodes, and publishes the newest position with
// its CLOCK_MONOTONIC arrival time. Malformed messages are counted (counters().bad) and dropped;
// other well-formed traffic is counted as ignored. start/stop/describe from one thread;
// latest()/counters() from any.

#include <cstdint>
#include <memory>
#include <string>

#include "avar/inputs/timecode_source.hpp"
#include "avar/inputs/udp_listener.hpp"

namespace avar::inputs {

/// ArtTimeCode packets on one UDP address (127.0.0.1:6454 unless told otherwise).
class ArtnetTimecodeInput final : public TimecodeSource {
 public:
  /// Throws std::invalid_argument for a host that is not IPv4.
  explicit ArtnetTimecodeInput(std::string host = "127.0.0.1", std::uint16_t port = 6454);
  void start() override;
  void stop() noexcept override { listener_.stop(); }
  TimecodeReading latest() const noexcept override { return mailbox_.read(); }
  TimecodeCounters counters() const noexcept override { return counters_.snapshot(); }
  std::string describe() const override { return "Art-Net timecode on udp " + listener_.where(); }
  std::uint16_t bound_port() const noexcept { return listener_.bound_port(); }

 private:
  UdpListener listener_;
  TimecodeMailbox mailbox_;
  AtomicTimecodeCounters counters_;
};

/// MIDI Time Code (quarter frames and full frames) from an ALSA sequencer port, chosen as
/// `avar inputs` lists them (a number or part of the name).
class MtcInput final : public TimecodeSource {
 public:
  explicit MtcInput(std::string port);
  ~MtcInput() override;
  MtcInput(const MtcInput&) = delete;
  MtcInput& operator=(const MtcInput&) = delete;
  /// Throws std::runtime_error when there is no sequencer or no such port.
  void start() override;
  void stop() noexcept override;
  TimecodeReading latest() const noexcept override { return mailbox_.read(); }
  TimecodeCounters counters() const noexcept override { return counters_.snapshot(); }
  std::string describe() const override;

  struct Device;

 private:
  std::string wanted_;
  std::string opened_;
  std::unique_ptr<Device> device_;
  TimecodeMailbox mailbox_;
  AtomicTimecodeCounters counters_;
};

}  // namespace avar::inputs
