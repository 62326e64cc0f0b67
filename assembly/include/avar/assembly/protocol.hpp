#pragma once
// The registry of protocols: everything avar knows about one kind of link, in one entry. A new
// protocol joins by one entry (its own source file under assembly/src/protocols/) and one line in
// the registry's list; the rig reader, the validation, the driver and the simulator all reach it
// through here. Load-time only: nothing here runs in the tick.

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
#include "avar/rig/rig.hpp"
#include "avar/sim/byte_device.hpp"
#include "avar/sim/sim_dmx_node.hpp"
#include "avar/sim/usb_control_device.hpp"

namespace avar::assembly {

/// How an actuator is addressed and calibrated on a link.
struct AddressRule {
  const char* key;      ///< device_channel, id or address
  long long low, high;  ///< valid addresses
  const char* cal_min;  ///< calibration keys
  const char* cal_max;
  const char* trim;
  double device_low, device_high;  ///< the device's own range
  const char* unit;
};

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
  const char* name;         ///< the settings block's key in a rig file: `maestro: {...}`
  const char* device_name;  ///< for messages: "Maestro"
  int default_baud;
  const char* bauds_text;  ///< the rates the device runs at, for messages
  bool (*device_accepts_baud)(int baud);
  /// Checks the link's settings whole (keys, types, ranges); throws InputError at the setting.
  void (*validate_settings)(const rig::LinkSpec& link);
  AddressRule (*address_rule)(const rig::LinkSpec& link, bool fine);
  /// Whether the actuator may set `fine` (16-bit DMX).
  bool has_fine_addresses;
  /// Whether an actuator must be calibrated (a DMX dimmer spans its range by default).
  bool needs_calibration;
  /// Whether the devices report telemetry (position, load, temperature) with these settings.
  bool (*reports_telemetry)(const rig::LinkSpec& link);
  /// The driver of link `link` of a validated rig over `transport` (borrowed).
  std::unique_ptr<firmware_iface::ActuatorLink> (*make_link)(const rig::Rig& rig, std::size_t link,
                                                             firmware_iface::ByteTransport& transport,
                                                             const DriverTuning& tuning);
  /// A simulated device set up as its owner would have set up the real one, parked at rest.
  SimulatedDevice (*make_simulated)(const rig::Rig& rig, std::size_t link);

  // Buses of drives (CAN) only; nullptr for every other protocol.

  /// Interprets an actuator's own keys (a.settings: everything but channel, link, the address,
  /// speed, acceleration and failsafe), fills a.drive and a.calibration. Throws InputError at
  /// the key. A protocol with this hook takes no calibration block.
  void (*finish_actuator)(const rig::Rig& rig, rig::ActuatorSpec& a) = nullptr;
  /// Checks a link's actuators together once all are read (identifiers that collide on the bus,
  /// a bitrate a drive cannot run at). Replaces the one-address-one-actuator check. Throws
  /// InputError at the offending actuator.
  void (*validate_link_actuators)(const rig::Rig& rig, std::size_t link) = nullptr;
  /// Opens a link whose port is no serial device (a SocketCAN interface, a Maestro on USB) and
  /// makes its driver; nullptr: FigureLinks opens a SerialTransport on the port and calls
  /// make_link. Not called for simulated links.
  std::unique_ptr<firmware_iface::ActuatorLink> (*open_link)(const rig::Rig& rig, std::size_t link,
                                                             const std::string& port) = nullptr;
  /// Whether the link's port (as written or given with --port) is a serial device (make_link)
  /// rather than something open_link opens.
  bool (*port_is_serial)(const rig::LinkSpec& link, const std::string& port) = nullptr;
  /// Whether the link may leave out its port because the device is found otherwise (a Maestro
  /// on USB by its serial number); the link's port is then "". Asked before validate_settings.
  bool (*port_optional)(const rig::LinkSpec& link) = nullptr;
  /// The driver of a link whose device is reached by USB control transfers, over `transport`
  /// (owned): the real device (from open_link) or a simulated one (SimulatedDevice::usb_device).
  std::unique_ptr<firmware_iface::ActuatorLink> (*make_usb_link)(const rig::Rig& rig, std::size_t link,
                                                                 std::unique_ptr<firmware_iface::UsbControlTransport> transport,
                                                                 const DriverTuning& tuning) = nullptr;
  /// The simulated devices need their own time to come up (a drive's cyclic heartbeat): their
  /// simulator runs on the wall clock until the first tick instead of waiting for the loop.
  bool simulation_runs_during_start = false;

  /// Keys an actuator on this protocol's links takes besides the common ones and its address key
  /// (gpio: active_low), as written into ActuatorSpec::settings. Not for buses of drives.
  std::vector<std::string_view> actuator_keys = {};
  /// Checks one actuator once read (its channel's kind, its own keys); throws InputError at the
  /// key. nullptr: nothing more to check.
  void (*check_actuator)(const rig::Rig& rig, const rig::ActuatorSpec& a) = nullptr;

  // Lines of a GPIO chip only; nullptr for every other protocol.

  /// The driver of a link whose port names a GPIO chip, over that chip (opened by FigureLinks
  /// through its GpioChips: real, or simulated for port sim). Replaces make_link, open_link and
  /// make_simulated.
  std::unique_ptr<firmware_iface::ActuatorLink> (*make_chip_link)(const rig::Rig& rig, std::size_t link,
                                                                  std::shared_ptr<firmware_iface::GpioChip> chip) = nullptr;
};

/// Every protocol avar speaks, in the order messages list them.
const std::vector<const Protocol*>& protocols();
/// The protocol called `name`, or nullptr.
const Protocol* find_protocol(std::string_view name);
/// The protocol of a link of a validated rig (std::invalid_argument when unknown).
const Protocol& protocol_of(const rig::LinkSpec& link);
/// "maestro, dynamixel, ..." for messages.
std::string protocol_names();

/// The baud rate written for a link of protocol `p` (`what` names it: "the baud rate of link
/// 'arm'"): a standard serial rate that the device runs at. Throws InputError at the value.
int checked_baud(const Protocol& p, const ScalarValue& written, std::string_view what);

/// Index of an actuator among its link's actuators (the order drivers and simulated devices
/// list them in).
std::size_t index_on_link(const rig::Rig& rig, const rig::ActuatorSpec& wanted);

}  // namespace avar::assembly
