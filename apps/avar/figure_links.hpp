#pragma once
// The links of a rig, opened for playing: each one a real serial port or a simulated device
// behind a pseudo-terminal (the real serial driver talks to it exactly as to hardware).

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "avar/control/rig.hpp"
#include "avar/firmware_iface/actuator_link.hpp"
#include "avar/firmware_iface/dmx_link.hpp"
#include "avar/firmware_iface/dynamixel_link.hpp"
#include "avar/firmware_iface/feetech_link.hpp"
#include "avar/firmware_iface/ssc32_link.hpp"
#include "avar/firmware_iface/maestro_link.hpp"

namespace avar::app {

struct LinkSelection {
  std::optional<std::string> port;  ///< overrides the port of the rig's single link
  bool simulate_all = false;        ///< simulate every link whatever its port says
  /// Serve each link from its own I/O thread with a watchdog (real time), at this tick rate;
  /// 0: send on the loop thread (stepped time, deterministic).
  double threaded_rate_hz = 0;
};

/// The Maestro driver settings for one link of the rig (calibrations and device-side limits).
firmware_iface::MaestroLinkConfig maestro_config(const control::Rig& rig, std::size_t link);
/// The DYNAMIXEL driver settings for one link of the rig.
firmware_iface::DynamixelLinkConfig dynamixel_config(const control::Rig& rig, std::size_t link);
firmware_iface::FeetechLinkConfig feetech_config(const control::Rig& rig, std::size_t link);
firmware_iface::Ssc32LinkConfig ssc32_config(const control::Rig& rig, std::size_t link);
firmware_iface::DmxLinkConfig dmx_config(const control::Rig& rig, std::size_t link);
/// The driver for one link of the rig, by its protocol, over `transport` (borrowed).
std::unique_ptr<firmware_iface::ActuatorLink> make_link(const control::Rig& rig, std::size_t link,
                                                        firmware_iface::ByteTransport& transport);

class FigureLinks {
 public:
  /// Opens every link: starts simulated devices first, then opens each port with the real
  /// serial transport. Throws InputError naming the port when one cannot be opened or the
  /// selection does not fit the rig (for example --port on a rig with several links).
  FigureLinks(const control::Rig& rig, const LinkSelection& selection);
  ~FigureLinks();
  FigureLinks(const FigureLinks&) = delete;
  FigureLinks& operator=(const FigureLinks&) = delete;

  std::vector<firmware_iface::ActuatorLink*> links() const;
  bool any_simulated() const;
  bool all_simulated() const;
  /// "Maestro on /dev/ttyACM0" or "simulated Maestro on /dev/pts/3".
  std::string describe(std::size_t link) const;

  /// Simulated time step, called after each tick on the loop thread: waits until every
  /// simulated device has taken in all bytes sent so far, advances its servos by dt_s, and
  /// writes their positions in channel units to measured[channel] (known[channel] = true).
  void step_simulation(double dt_s, std::span<double> measured, std::span<bool> known);

  std::size_t link_count() const { return entries_.size(); }
  /// One link's wire counters (ActuatorLink::counters), any thread.
  firmware_iface::LinkCounters counters(std::size_t link) const;
  /// Whether a link's devices report telemetry (smart servo buses).
  bool reports_telemetry(std::size_t link) const;

  /// Every link's newest device telemetry into telemetry[channel] (see ActuatorLink).
  void read_telemetry(std::span<firmware_iface::ChannelTelemetry> telemetry) const;

  /// Total bytes written to every link.
  std::uint64_t bytes_sent() const;

  struct Entry;

 private:
  const control::Rig& rig_;
  std::vector<std::unique_ptr<Entry>> entries_;
};

}  // namespace avar::app
