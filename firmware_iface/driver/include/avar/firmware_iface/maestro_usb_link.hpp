#pragma once
// The Pololu Maestro driver over native USB (maestro_usb_codec.hpp): hobby servos on a Maestro
// driven by vendor control requests, beside the serial driver (MaestroLink), with which it shares
// its actuators' checks, limits and targets (maestro_actuators.hpp). Per tick it sends one Set
// Target request per actuator, then reads every channel's output pulse in one request (Get
// Variables on the Micro Maestro, Get Servo Settings on a Mini) as telemetry: the position the
// Maestro drives after its own speed and acceleration limits, not a measured one. A tick whose
// transfers time out, stall or come back short costs that tick's telemetry only; `silent_ticks`
// such ticks in a row make send() report a timeout (the controller's watchdog fault), as the
// serial buses' silence budget does (DeviceWatch: device_watch.hpp). A Maestro that is gone (an I/O error) fails the link at
// once.
//
// Threads: send(), release(), read_telemetry() on one thread (the loop's or the link's I/O
// thread); release_channel(), saturated_pulses() and counters() from any thread. send() and
// release() allocate nothing here; the transport may (libusb does, inside each transfer).

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "avar/firmware_iface/actuator_link.hpp"
#include "avar/firmware_iface/actuator_table.hpp"
#include "avar/firmware_iface/atomic_link_counters.hpp"
#include "avar/firmware_iface/device_watch.hpp"
#include "avar/firmware_iface/maestro_actuators.hpp"
#include "avar/firmware_iface/maestro_usb_codec.hpp"
#include "avar/firmware_iface/reconnector.hpp"
#include "avar/firmware_iface/usb_control_transport.hpp"

namespace avar::firmware_iface {

struct MaestroUsbLinkConfig {
  int channel_count = 24;                  ///< 6 (Micro Maestro), 12, 18 or 24 (Mini Maestro)
  std::chrono::milliseconds timeout{100};  ///< per control transfer
  std::uint32_t silent_ticks = 10;         ///< failed ticks in a row that make send() a timeout; >= 1
  std::vector<MaestroActuator> actuators;
};

class MaestroUsbLink final : public ActuatorLink {
 public:
  /// Sizes every buffer. Throws std::invalid_argument for a channel count other than 6, 12, 18
  /// or 24, a device channel out of range or used twice, or a silent_ticks of 0.
  MaestroUsbLink(std::unique_ptr<UsbControlTransport> transport, MaestroUsbLinkConfig config);

  /// Reads the error register (kept for start_problem()), clears it, and sends each actuator's
  /// speed and acceleration limits. Not real-time.
  Status start() override;
  std::string start_problem() const override { return start_problem_; }
  /// The pulse each actuator's channel outputs now, in channel units. A channel that outputs
  /// no pulse (0, e.g. after power-up) is left unknown.
  Status read_positions(std::span<double> frame, std::span<bool> known) override;
  /// Sets every actuator's target, then reads the output pulses as telemetry (a failed read
  /// leaves the positions unknown, not old). A timed-out, stalled or short transfer is ok until
  /// the silence budget runs out (counted in counters()); an I/O error is returned at once.
  Status send(std::span<const double> frame) noexcept override;
  /// Target 0 on every actuator: no more pulses.
  Status release() noexcept override;
  void release_channel(std::size_t channel) noexcept override { table_.release_channel(channel); }
  std::uint64_t saturated_pulses() const noexcept override { return table_.saturated(); }
  const std::string& describe() const noexcept override { return description_; }
  void read_telemetry(std::span<ChannelTelemetry> out) const noexcept override { table_.read_telemetry(out); }
  LinkCounters counters() const noexcept override;

  /// The error register (maestro::ErrorBit), without clearing it.
  Status read_errors(std::uint16_t& errors) noexcept;

 private:
  /// One control transfer, counted. Marks the link lost on an I/O error.
  Status transfer(const UsbSetup& setup, std::span<std::uint8_t> data, std::size_t* got) noexcept;
  /// Speed and acceleration of every actuator (start, and after a reconnect).
  Status send_limits() noexcept;
  /// Output pulses of every channel into reply_; ok only with every record there.
  Status read_records() noexcept;
  Status write_targets() noexcept;
  /// A failed tick within the silence budget is ok; a whole one answers the watch.
  Status judge_silence(Status tick) noexcept;

  std::unique_ptr<UsbControlTransport> transport_;
  MaestroUsbLinkConfig config_;
  ActuatorTable table_;
  std::vector<std::uint16_t> targets_;  ///< quarter-µs per actuator, rebuilt each send
  std::vector<std::uint8_t> reply_;     ///< the servo records, sized once
  std::string description_;
  std::string start_problem_;
  Reconnector reconnector_;
  AtomicLinkCounters counters_;
  DeviceWatch silence_;  ///< ticks in a row without a whole exchange (send's thread)
};

}  // namespace avar::firmware_iface
