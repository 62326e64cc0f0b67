#pragma once
// The ENTTEC DMX USB Pro driver over any ByteTransport: one DMX universe of 8-bit (one slot) and
// 16-bit (coarse slot at `address`, fine slot at address + 1) actuators, the whole frame sent
// every tick as one Output Only Send DMX message in one write. DMX is one-way: no read-back.

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "avar/firmware_iface/actuator_link.hpp"
#include "avar/firmware_iface/byte_transport.hpp"
#include "avar/firmware_iface/dmx_codec.hpp"
#include "avar/firmware_iface/dmx_universe.hpp"
#include "avar/firmware_iface/reconnector.hpp"

namespace avar::firmware_iface {

struct DmxLinkConfig {
  /// Slots sent per frame: 0 = up to the highest slot an actuator uses (at least 24).
  std::size_t slot_count = 0;
  std::chrono::milliseconds reply_timeout{200};  ///< start()'s Get Widget Parameters
  std::vector<DmxActuator> actuators;
};

class DmxLink final : public ActuatorLink {
 public:
  /// Throws std::invalid_argument for no actuators, an address outside 1..512 (511 for fine),
  /// two actuators sharing a slot, or a slot_count that leaves an actuator out.
  DmxLink(ByteTransport& transport, DmxLinkConfig config);

  /// Asks the widget for its parameters: one that does not answer in time is a timeout.
  Status start() override;
  /// DMX reports nothing: leaves everything untouched.
  Status read_positions(std::span<double> frame, std::span<bool> known) override;
  /// Real-time safe: one write of the whole frame.
  Status send(std::span<const double> frame) noexcept override;
  /// Sends every actuator's slots at level 0 (DMX has no "off"; DMX servo decoders commonly
  /// stop their pulses at 0, unconfirmed). Real-time safe.
  Status release() noexcept override;
  /// From the next send on, the channel's slots go to level 0.
  void release_channel(std::size_t channel) noexcept override;
  std::uint64_t saturated_pulses() const noexcept override { return universe_.saturated(); }
  const std::string& describe() const noexcept override { return description_; }
  /// Only reconnects: the device does not answer every tick.
  LinkCounters counters() const noexcept override { return reconnector_.counters(); }

  /// The widget's parameters as start() read them.
  const dmx::WidgetParameters& widget_parameters() const noexcept { return parameters_; }
  std::size_t slot_count() const noexcept { return universe_.slots().size(); }
  std::size_t last_send_size() const noexcept { return last_send_size_; }

 private:
  Status write_frame() noexcept;

  ByteTransport& transport_;
  DmxLinkConfig config_;
  std::string description_;
  DmxUniverse universe_;
  std::vector<std::uint8_t> packet_;
  dmx::WidgetParameters parameters_;
  std::size_t last_send_size_ = 0;
  Reconnector reconnector_;  ///< reopens the port after an I/O error
};

}  // namespace avar::firmware_iface
