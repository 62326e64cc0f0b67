#pragma once
// The registry of protocols: how avar opens one kind of link, in one entry. What a protocol's
// settings are and how they parse is its schema in the rig (avar/rig/protocol_schema.hpp); an
// entry here turns a parsed link into its driver and its simulated device. A new protocol joins
// by a schema, one entry (its own source file under assembly/src/protocols/) and one line in the
// registry's list. Load-time only: nothing here runs in the tick.

#include <algorithm>
#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "avar/firmware_iface/actuator_link.hpp"
#include "avar/firmware_iface/byte_transport.hpp"
#include "avar/firmware_iface/gpio_chip.hpp"
#include "avar/firmware_iface/usb_control_transport.hpp"
#include "avar/assembly/sim_offer.hpp"
#include "avar/rig/protocol_schema.hpp"
#include "avar/rig/rig.hpp"
#include "avar/sim/byte_device.hpp"
#include "avar/sim/sim_dmx_node.hpp"
#include "avar/sim/usb_control_device.hpp"

namespace avar::assembly {

/// A simulated device for one link of a rig, and how to read an actuator's true position off it
/// (channel units: the ground truth the simulator knows and a real figure never tells).
struct SimulatedDevice {
  /// A device behind a serial port: served on a pseudo-terminal to the driver of make_link.
  std::unique_ptr<sim::ByteDevice> device;
  std::function<double(const rig::ActuatorSpec&)> true_position;
  /// Instead of `device`, a device driven by USB control transfers: served in this process to
  /// the driver of make_usb_link, its connection named usb_name ("USB (serial 00012345)").
  std::unique_ptr<sim::UsbControlDevice> usb_device = nullptr;
  std::string usb_name = {};
  /// Instead of `device`, a node on the network (Art-Net, sACN) listening on loopback: the
  /// protocol's open_link sends to its endpoint().
  std::unique_ptr<sim::SimDmxNode> network_node = nullptr;
};

/// What the assembly asks of a driver beyond the rig.
struct DriverTuning {
  /// Smallest wait for a reply (ms): a simulated device answers from a thread of this process,
  /// which a busy machine may keep waiting longer than a real servo's reply timeout.
  int min_reply_timeout_ms = 0;

  /// A driver's configured reply timeout, raised to the minimum above.
  std::chrono::milliseconds reply_timeout(std::chrono::milliseconds configured) const {
    return std::max(configured, std::chrono::milliseconds(min_reply_timeout_ms));
  }
};

struct Protocol {
  const char* name;  ///< its schema's name (rig::find_schema): `maestro`
  /// The driver of link `link` of a validated rig over `transport` (borrowed).
  std::unique_ptr<firmware_iface::ActuatorLink> (*make_link)(const rig::Rig& rig, std::size_t link,
                                                             firmware_iface::ByteTransport& transport,
                                                             const DriverTuning& tuning);
  /// A simulated device set up as its owner would have set up the real one, parked at rest.
  SimulatedDevice (*make_simulated)(const rig::Rig& rig, std::size_t link);

  /// Opens a link whose port is no serial device (a SocketCAN interface, a Maestro on USB) and
  /// makes its driver; nullptr: FigureLinks opens a SerialTransport on the port and calls
  /// make_link. Not called for simulated links.
  std::unique_ptr<firmware_iface::ActuatorLink> (*open_link)(const rig::Rig& rig, std::size_t link,
                                                             const std::string& port) = nullptr;
  /// Whether the link's port (as written or given with --port) is a serial device (make_link)
  /// rather than something open_link opens.
  bool (*port_is_serial)(const rig::LinkSpec& link, const std::string& port) = nullptr;
  /// The driver of a link whose device is reached by USB control transfers, over `transport`
  /// (owned): the real device (from open_link) or a simulated one (SimulatedDevice::usb_device).
  std::unique_ptr<firmware_iface::ActuatorLink> (*make_usb_link)(const rig::Rig& rig, std::size_t link,
                                                                 std::unique_ptr<firmware_iface::UsbControlTransport> transport,
                                                                 const DriverTuning& tuning) = nullptr;
  /// The simulated devices need their own time to come up (a drive's cyclic heartbeat): their
  /// simulator runs on the wall clock until the first tick instead of waiting for the loop.
  bool simulation_runs_during_start = false;

  // Lines of a GPIO chip only; nullptr for every other protocol.

  /// The driver of a link whose port names a GPIO chip, over that chip (opened by FigureLinks
  /// through its GpioChips: real, or simulated for port sim). Replaces make_link, open_link and
  /// make_simulated.
  std::unique_ptr<firmware_iface::ActuatorLink> (*make_chip_link)(const rig::Rig& rig, std::size_t link,
                                                                  std::shared_ptr<firmware_iface::GpioChip> chip) = nullptr;

  /// What `avar sim NAME` serves for this protocol.
  SimOffer sim = {};
};

/// Every protocol avar speaks, in the order messages list them.
const std::vector<const Protocol*>& protocols();
/// The protocol called `name`, or nullptr.
const Protocol* find_protocol(std::string_view name);
/// The protocol of a link of a validated rig (std::invalid_argument when unknown).
const Protocol& protocol_of(const rig::LinkSpec& link);
/// Its schema.
const rig::ProtocolSchema& schema_of(const Protocol& p);

using rig::index_on_link;

}  // namespace avar::assembly
