#pragma once
// The links of a rig, opened for playing: each one a real serial port (or USB device, or CAN
// interface) or a simulated device behind a pseudo-terminal (the real serial driver talks to it
// exactly as to hardware) or at the USB control-transfer seam (the real USB driver makes its
// transfers to it). Drivers and simulated devices come from the protocol registry (protocol.hpp).

#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "avar/assembly/gpio_chips.hpp"
#include "avar/assembly/protocol.hpp"
#include "avar/control/plant.hpp"
#include "avar/firmware_iface/actuator_link.hpp"
#include "avar/rig/rig.hpp"
#include "avar/sim/usb_device_host.hpp"

namespace avar::assembly {

struct LinkSelection {
  std::optional<std::string> port;  ///< overrides the port of the rig's single link
  bool simulate_all = false;        ///< simulate every link whatever its port says
  /// Serve each link from its own I/O thread with a watchdog (real time), at this tick rate;
  /// 0: send on the loop thread (stepped time, deterministic).
  double threaded_rate_hz = 0;
  /// Called once for each simulated device behind a serial port before anything talks to it (a
  /// test heating a servo, loading a horn); empty: none.
  std::function<void(std::size_t link, sim::ByteDevice& device)> prepare_simulated;
  /// The GPIO chips that gpio links open, shared with the rig's digital inputs (so a simulated
  /// chip's buttons and relays are one set of lines); null: FigureLinks keeps its own.
  std::shared_ptr<GpioChips> gpio_chips;
};

/// The figure's links, and for simulated ones the plant the loop advances (control::Plant) and
/// the ground truth it measures (control::PositionSource).
class FigureLinks final : public control::PositionSource, public control::Plant {
 public:
  /// Opens every link: starts simulated devices first, then opens each port with the real
  /// serial transport (or, for a protocol that opens its own, such as a SocketCAN interface,
  /// through the protocol; a gpio link on its chip from LinkSelection::gpio_chips). Throws InputError naming the port when one
  /// cannot be opened or the selection does not fit the rig (for example --port on a rig with several links).
  FigureLinks(const rig::Rig& rig, const LinkSelection& selection);
  ~FigureLinks() override;
  FigureLinks(const FigureLinks&) = delete;
  FigureLinks& operator=(const FigureLinks&) = delete;

  std::vector<firmware_iface::ActuatorLink*> links() const;
  bool any_simulated() const;
  bool all_simulated() const;
  /// "Maestro on /dev/ttyACM0" or "simulated Maestro on /dev/pts/3".
  std::string describe(std::size_t link) const;

  /// Simulated time step, after each tick on the loop thread: waits until every simulated
  /// device has taken in all bytes sent so far, advances its servos by dt_s, and keeps their
  /// true positions for measure().
  void advance(double dt_s) override;
  /// The simulated actuators' true positions as of the last advance(), in channel units (a
  /// simulated GPIO line: the channel value its level stands for).
  /// Channels on real links are left unknown. Real-time safe.
  void measure(std::span<double> measured, std::span<bool> known) const noexcept override;

  std::size_t link_count() const { return entries_.size(); }
  /// Runs f on a simulated link's device under its host's lock, so that a test may change it
  /// while it runs (a drive dropping off the bus mid-show). Throws std::invalid_argument for a
  /// link that is not simulated.
  void with_simulated(std::size_t link, const std::function<void(sim::ByteDevice&)>& f);
  /// The same for a link simulated on USB: f gets the device's host (with_device to reach the
  /// device under its lock, set_plugged to unplug it). Throws std::invalid_argument for a link
  /// that is not simulated on USB.
  void with_simulated_usb(std::size_t link, const std::function<void(sim::UsbDeviceHost&)>& f);
  /// A link's simulated network node (Art-Net, sACN), for tests to watch or to send it bad
  /// packets between ticks; nullptr for other links. On the loop thread, between ticks.
  sim::SimDmxNode* simulated_node(std::size_t link) const;
  /// One link's wire counters (ActuatorLink::counters), any thread.
  firmware_iface::LinkCounters counters(std::size_t link) const;
  /// What the device driving `channel` said of its fault (ActuatorLink::channel_problem); after
  /// the loop stopped.
  std::string channel_problem(std::size_t channel) const;
  /// Whether a link's devices report telemetry (smart servo buses).
  bool reports_telemetry(std::size_t link) const;

  /// Total bytes written to every link.
  std::uint64_t bytes_sent() const;

  struct Entry;

 private:
  const rig::Rig& rig_;
  std::vector<std::unique_ptr<Entry>> entries_;
  std::vector<double> truth_;      ///< per channel, as of the last advance()
  std::vector<char> truth_known_;  ///< per channel
  std::shared_ptr<GpioChips> gpio_chips_;
};

}  // namespace avar::assembly
