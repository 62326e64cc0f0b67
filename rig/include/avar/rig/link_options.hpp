#pragma once
// Each protocol's link settings, and the settings of an actuator on a bus of drives, parsed once
// at load into typed options (avar::rig::ProtocolSchema). Plain data: drivers and simulated
// devices read these, nobody re-reads the text. Where a setting may still be refused once the
// device is reached (a Maestro's serial number on USB, a network destination replaced on the
// command line), the options keep where it was written.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>

#include "avar/core/input_error.hpp"
#include "avar/firmware_iface/mit_can_codec.hpp"

namespace avar::rig {

/// What a smart-servo bus reads back every tick.
enum class Readback {
  none,      ///< write only
  position,  ///< present position
  full,      ///< position, load, temperature (and hardware errors on alert)
};

/// The settings every polled smart-servo bus shares: `{readback, reply_timeout_ms, retries}`.
struct ServoBusOptions {
  Readback readback = Readback::full;
  int reply_timeout_ms = 10;  ///< longest wait for one exchange's replies
  int retries = 1;            ///< re-reads per exchange for lost replies
};

/// `maestro: {model, device_number, crc, baud_detect}` on a serial port, or `maestro: {model,
/// usb}` on native USB.
struct MaestroOptions {
  int channel_count = 24;    ///< 6 (Micro), 12, 18 or 24 (Mini)
  bool pololu_form = false;  ///< address by device number (daisy chains) instead of compact
  std::uint8_t device_number = 12;
  bool crc = false;          ///< append CRC-7 (the device's "Enable CRC" setting)
  bool baud_detect = false;  ///< send 0xAA first (device in "UART, detect baud rate" mode)
  bool usb = false;          ///< native USB (vendor requests) instead of a serial port
  std::string usb_serial;    ///< with usb: the serial number string; empty: the only Maestro present
  SourceLocation usb_where;  ///< with usb: where the setting stands (a missing device is reported there)
};

/// `dynamixel: {readback, reply_timeout_ms, retries}` (Protocol 2.0).
struct DynamixelOptions {
  ServoBusOptions bus;
};

/// Feetech servo series: STS (12-bit, 0..4095) or SCS (10-bit, 0..1023).
enum class FeetechSeries { sts, scs };

/// `feetech: {series, readback, reply_timeout_ms, retries}`.
struct FeetechOptions {
  ServoBusOptions bus;
  FeetechSeries series = FeetechSeries::sts;
};

/// `ssc32: {}`: no settings of its own.
struct Ssc32Options {};

/// `dmx: {}` (a USB DMX widget): no settings of its own.
struct DmxOptions {};

/// `gpio: {}`: no settings of its own (the port names the chip).
struct GpioOptions {};

/// `pca9685: {address, frequency, clock, outputs}`: a PCA9685 board on the I2C bus the port
/// names (/dev/i2c-1).
struct Pca9685Options {
  int address = 0x40;             ///< 7-bit I2C address (0x40 with no jumper)
  int frequency_hz = 50;          ///< the pulses' rate: 50 for hobby servos
  long long clock_hz = 25000000;  ///< the board's oscillator (a measured value, or an external clock)
  bool totem_pole = true;         ///< outputs: totem_pole (the boards') or open_drain
};

/// `pwm: {frequency}`: hobby servos on the outputs of the PWM chip the port names (pwmchip0), or
/// on a microcontroller's own pins when exported.
struct PwmOptions {
  int frequency_hz = 50;  ///< pulses per second: 50 for hobby servos
};

/// `avar-device: {knot_ms, lead_ms, device_rate, device_knots, device_watchdog_ms}`: a device
/// running avar's streaming player on the serial port (docs/protocols/avar-device.md).
/// The device_* settings describe the device: the simulated one is built with them, a real one
/// is checked against what it reports (its knot room).
struct AvarDeviceOptions {
  int knot_ms = 50;              ///< a knot every this many ms (a whole number of ticks)
  int lead_ms = 150;             ///< how far ahead of its time a knot is sent
  int device_rate_hz = 200;      ///< the device's control ticks per second
  int device_knots = 16;         ///< knot frames the device holds
  int device_watchdog_ms = 500;  ///< link silence after which the device eases to rest
};

/// How a CAN link reaches its bus.
enum class CanInterface {
  by_port,    ///< not written: SLCAN for a device path (/dev/...), SocketCAN otherwise
  slcan,      ///< a serial adapter (CANable, USBtin)
  socketcan,  ///< a Linux CAN interface (can0)
};

/// `can: {bitrate, interface, reply_timeout_ms, heartbeat_ms, heartbeat_timeout_ms, mit_master_id}`.
struct CanOptions {
  int bitrate = 1'000'000;  ///< bit/s
  CanInterface interface = CanInterface::by_port;
  int reply_timeout_ms = 5;                 ///< longest a tick waits for the drives' replies
  int heartbeat_ms = 100;                   ///< heartbeat period the drives produce
  std::optional<int> heartbeat_timeout_ms;  ///< silence before a drive is lost; default 3 heartbeats
  std::uint32_t mit_master_id = 0;          ///< the id MIT-style motors reply to
  /// The silence budget in seconds: heartbeat_timeout_ms, or three heartbeats.
  double heartbeat_timeout_s() const { return (heartbeat_timeout_ms ? *heartbeat_timeout_ms : 3.0 * heartbeat_ms) / 1000.0; }
};

/// A network destination as written (`to: HOST[:PORT]`), validated at load.
struct NetworkTarget {
  std::string text;      ///< "" when not written
  SourceLocation where;  ///< where `to` stands, else the settings block
};

/// `artnet: {to, broadcast, net, subnet, universe, slots}`: Art-Net 4 ArtDmx, one universe.
struct ArtnetOptions {
  NetworkTarget to;
  bool broadcast = false;
  unsigned net = 0;       ///< 0..127
  unsigned subnet = 0;    ///< 0..15
  unsigned universe = 0;  ///< 0..15
  std::size_t slots = 0;  ///< slots sent per frame; 0: as many as the actuators need
};

/// `sacn: {to, universe, priority, source_name, cid, preview, multicast_ttl, multicast_interface,
/// discovery, slots}`: E1.31, one universe.
struct SacnOptions {
  NetworkTarget to;  ///< empty: the universe's multicast group
  std::uint16_t universe = 1;
  std::uint8_t priority = 100;
  std::optional<std::string> source_name;           ///< at most 63 bytes; default "avar RIG LINK"
  std::optional<std::array<std::uint8_t, 16>> cid;  ///< default: derived from the rig's and link's names
  bool preview = false;
  int multicast_ttl = 1;
  std::string multicast_interface;  ///< IPv4 address of the sending interface, "" for the default
  bool discovery = true;
  std::size_t slots = 0;
};

/// One link's settings, by protocol (monostate only in a LinkSpec not read from a file).
using LinkOptions =
    std::variant<std::monostate, MaestroOptions, DynamixelOptions, FeetechOptions, Ssc32Options, DmxOptions, CanOptions,
                 GpioOptions, ArtnetOptions, SacnOptions, Pca9685Options, AvarDeviceOptions, PwmOptions>;

/// A GPIO output line's own setting.
struct GpioOutputOptions {
  bool active_low = false;  ///< the line is low while the channel is on
};

/// ODrive input filter mode.
enum class OdriveInputMode { passthrough, pos_filter, trap_traj };

/// An ODrive axis on a CAN link: `current_limit` (A), `input_mode`.
struct OdriveOptions {
  double current_limit = 10;
  OdriveInputMode input_mode = OdriveInputMode::passthrough;
};

/// A CiA 402 drive on a CAN link: `counts_per_turn` (the drive's position counts per motor turn).
struct Cia402Options {
  double counts_per_turn = 0;
  SourceLocation counts_where;
};

/// An MIT-style motor on a CAN link: its model's value ranges and its gains.
struct MitOptions {
  firmware_iface::mit::MitRanges ranges = firmware_iface::mit::kMiniCheetahRanges;
  double kp = 20;   ///< N·m/rad
  double kd = 0.5;  ///< N·m·s/rad
};

/// An actuator's own options, by its link's protocol (monostate where it has none).
using ActuatorOptions = std::variant<std::monostate, GpioOutputOptions, OdriveOptions, Cia402Options, MitOptions>;

}  // namespace avar::rig
