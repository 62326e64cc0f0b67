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
#include "avar/firmware_iface/i2c_bus.hpp"
#include "avar/firmware_iface/pwm_chip.hpp"
#include "avar/firmware_iface/serial_transport.hpp"
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
  /// A device behind a serial port: served on a pseudo-terminal to the link's driver.
  std::unique_ptr<sim::ByteDevice> device;
  std::function<double(const rig::ActuatorSpec&)> true_position;
  /// Instead of `device`, a device driven by USB control transfers: served in this process to
  /// the link's driver, its connection named usb_name ("USB (serial 00012345)").
  std::unique_ptr<sim::UsbControlDevice> usb_device = nullptr;
  std::string usb_name = {};
  /// Instead of `device`, a node on the network (Art-Net, sACN) listening on loopback: the
  /// link's driver sends to its endpoint().
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

/// Where a link's driver talks: one of a port, a byte transport, a USB device, a GPIO chip, an
/// I2C bus or a PWM chip.
struct LinkEndpoint {
  /// A serial device (/dev/ttyACM0, or a simulated device's pseudo-terminal), a SocketCAN
  /// interface (can0), a network destination (HOST[:PORT]), or "" for a device the rig finds
  /// otherwise (a Maestro on USB by its serial number, a network node the rig names).
  std::string port;
  /// The port is the pseudo-terminal of a simulated device (a byte device, whatever the rig says).
  bool simulated = false;
  /// Instead of a port: a byte transport the caller owns and keeps until the driver goes.
  firmware_iface::ByteTransport* bytes = nullptr;
  /// Instead of a port: a device reached by USB control transfers (the driver takes it).
  std::unique_ptr<firmware_iface::UsbControlTransport> usb = nullptr;
  /// Instead of a port: the GPIO chip of a link on a chip's lines (real, or simulated).
  std::shared_ptr<firmware_iface::GpioChip> chip = nullptr;
  /// Instead of a port: the I2C bus of a link on a bus (real, or simulated with its board).
  std::shared_ptr<firmware_iface::I2cBus> i2c = nullptr;
  /// Instead of a port: the PWM chip of a link on a chip's outputs (real, or simulated).
  std::shared_ptr<firmware_iface::PwmChip> pwm = nullptr;
  DriverTuning tuning = {};
};

/// A link's driver, and the serial port it borrows when open opened one (closed after the driver).
struct OpenedLink {
  std::unique_ptr<firmware_iface::ActuatorLink> driver;
  std::unique_ptr<firmware_iface::SerialTransport> serial;
};

struct Protocol {
  const char* name;  ///< its schema's name (rig::find_schema): `maestro`
  /// The one way to make the driver of link `link` of a parsed rig: over the endpoint given (a
  /// real device, or a simulated one served by the caller). Throws InputError at the link's
  /// settings for a device that cannot be reached as the rig says.
  OpenedLink (*open)(const rig::Rig& rig, std::size_t link, LinkEndpoint at);
  /// A simulated device set up as its owner would have set up the real one, parked at rest.
  /// nullptr for links on a GPIO chip, an I2C bus or a PWM chip, which FigureLinks simulates itself.
  SimulatedDevice (*make_simulated)(const rig::Rig& rig, std::size_t link);
  /// The link's port names a GPIO chip: FigureLinks opens it (real or simulated) for `open`.
  bool on_gpio_chip = false;
  /// The link's port names an I2C bus: FigureLinks opens it (real, or simulated with the
  /// link's board on it) for `open`.
  bool on_i2c_bus = false;
  /// The link's port names a PWM chip: FigureLinks opens it (real, or simulated) for `open`.
  bool on_pwm_chip = false;
  /// The simulated devices need their own time to come up (a drive's cyclic heartbeat): their
  /// simulator runs on the wall clock until the first tick instead of waiting for the loop.
  bool simulation_runs_during_start = false;
  /// What `avar sim NAME` serves for this protocol.
  SimOffer sim = {};
};

/// A driver over bytes: `at.bytes` when given, else a serial port opened on `at.port` at the
/// link's baud rate. `make` builds the protocol's driver over that transport.
OpenedLink open_over_bytes(const rig::Rig& rig, std::size_t link, const LinkEndpoint& at,
                           std::unique_ptr<firmware_iface::ActuatorLink> (*make)(const rig::Rig& rig, std::size_t link,
                                                                                 firmware_iface::ByteTransport& transport,
                                                                                 const DriverTuning& tuning));

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
