#pragma once
// The fault matrix's axes: the protocols avar speaks (each a small rig of two channels on one
// link, port sim) and the faults injected between driver and simulated device, with which cells
// apply and why the others do not.

#include <array>
#include <cstddef>
#include <string_view>

namespace avar::fault_matrix {

enum class FaultKind { drop, corrupt, truncate, delay, duplicate, reorder, disconnect, silent, garbage };
inline constexpr std::size_t kFaultCount = 9;
inline constexpr std::array<FaultKind, kFaultCount> kFaults{FaultKind::drop,       FaultKind::corrupt,   FaultKind::truncate,
                                                            FaultKind::delay,      FaultKind::duplicate, FaultKind::reorder,
                                                            FaultKind::disconnect, FaultKind::silent,    FaultKind::garbage};

inline const char* fault_name(FaultKind f) {
  static constexpr std::array<const char*, kFaultCount> names{"drop",    "corrupt",    "truncate", "delay",  "duplicate",
                                                              "reorder", "disconnect", "silent",   "garbage"};
  return names[static_cast<std::size_t>(f)];
}

/// How the link reaches its device, which decides where faults are injected.
enum class Carrier {
  serial,   ///< bytes on a serial line: FaultyDevice behind a SimWire (the real driver's transport seam)
  pty,      ///< the same, served on a pseudo-terminal to the real SerialTransport
  usb,      ///< control transfers: FaultyUsbDevice behind a UsbDeviceHost
  network,  ///< UDP datagrams: FaultyDatagramPath between the link's socket and the node
  none,     ///< no wire between driver and device: every cell is n/a
};

/// Why a cell does not apply (an index into kNotApplicableReasons), or kApplies.
inline constexpr int kApplies = -1;
inline constexpr std::array<const char*, 9> kNotApplicableReasons{
    "the driver reads nothing while the show plays (write only): a reply fault cannot reach it",
    "USB control transfers are CRC-checked, retried and delivered whole by the host controller",
    "one-way UDP: the link reads nothing back",
    "UDP's checksum drops a corrupted datagram on the way: that is the drop column",
    "UDP delivers a datagram whole or not at all",
    "a pseudo-terminal cannot be unplugged: the in-memory wire rows cover the reopen",
    "a GPIO line is set by a call into this machine's kernel: no wire, no replies",
    "an I2C write is one transaction through the kernel, acknowledged or not: no replies; a board that "
    "stops acknowledging is counted and retried (tests/firmware_iface/pca9685_link_test.cpp)",
    "a PWM output is set by a write to this machine's kernel: no wire, no replies; a chip that refuses is "
    "counted and retried (tests/firmware_iface/pwm_link_test.cpp)",
};

struct ProtocolCase {
  const char* name;  ///< the matrix's row name; also the test's parameter name
  Carrier carrier;
  const char* rig_text;
  /// Per FaultKind: kApplies, or the reason it does not.
  std::array<int, kFaultCount> not_applicable;
};

/// Reply faults (corrupt, truncate, delay, duplicate, reorder, silent) cannot reach a driver
/// that reads nothing while playing.
inline constexpr std::array<int, kFaultCount> kWriteOnly{kApplies, 0, 0, 0, 0, 0, kApplies, 0, kApplies};
inline constexpr std::array<int, kFaultCount> kReadsReplies{kApplies, kApplies, kApplies, kApplies, kApplies,
                                                            kApplies, kApplies, kApplies, kApplies};
inline constexpr std::array<int, kFaultCount> kPty{kApplies, kApplies, kApplies, kApplies, kApplies,
                                                   kApplies, 5,        kApplies, kApplies};
inline constexpr std::array<int, kFaultCount> kUsb{kApplies, 1, kApplies, kApplies, 1, 1, kApplies, kApplies, kApplies};
inline constexpr std::array<int, kFaultCount> kNoWire{6, 6, 6, 6, 6, 6, 6, 6, 6};
inline constexpr std::array<int, kFaultCount> kI2c{7, 7, 7, 7, 7, 7, 7, 7, 7};
inline constexpr std::array<int, kFaultCount> kPwmChip{8, 8, 8, 8, 8, 8, 8, 8, 8};
inline constexpr std::array<int, kFaultCount> kNetwork{kApplies, 3, 4, kApplies, kApplies, kApplies, kApplies, 2, 2};

#define AVAR_FM_CHANNELS                                                                      \
  "rate_hz: 100\n"                                                                            \
  "channels:\n"                                                                               \
  "  a: {unit: deg, min: -45, max: 45, rest: 0, max_velocity: 200, max_acceleration: 2000}\n" \
  "  b: {unit: deg, min: -45, max: 45, rest: 0, max_velocity: 200, max_acceleration: 2000}\n"

inline const std::array<ProtocolCase, 16>& protocol_cases() {
  static const std::array<ProtocolCase, 16> cases{{
      {"maestro_serial", Carrier::serial,
       "name: fm-maestro\n" AVAR_FM_CHANNELS
       "links:\n  bus: {port: sim, baud: 115200, watchdog_ms: 200, maestro: {model: mini12}}\n"
       "actuators:\n"
       "  - {channel: a, link: bus, device_channel: 0, calibration: {min_us: 1000, max_us: 2000}}\n"
       "  - {channel: b, link: bus, device_channel: 1, calibration: {min_us: 1100, max_us: 1900, reverse: true}}\n",
       kWriteOnly},
      {"maestro_usb", Carrier::usb,
       "name: fm-maestro-usb\n" AVAR_FM_CHANNELS
       "links:\n  bus: {watchdog_ms: 200, maestro: {model: mini12, usb: \"00012345\"}}\n"
       "actuators:\n"
       "  - {channel: a, link: bus, device_channel: 0, calibration: {min_us: 1000, max_us: 2000}}\n"
       "  - {channel: b, link: bus, device_channel: 1, calibration: {min_us: 1100, max_us: 1900, reverse: true}}\n",
       kUsb},
      {"ssc32", Carrier::serial,
       "name: fm-ssc32\n" AVAR_FM_CHANNELS "links:\n  bus: {port: sim, baud: 115200, watchdog_ms: 200, ssc32: {}}\n"
       "actuators:\n"
       "  - {channel: a, link: bus, device_channel: 0, calibration: {min_us: 1000, max_us: 2000}}\n"
       "  - {channel: b, link: bus, device_channel: 5, calibration: {min_us: 1100, max_us: 1900}}\n",
       kWriteOnly},
      {"dmx_enttec", Carrier::serial,
       "name: fm-dmx\n" AVAR_FM_CHANNELS "links:\n  bus: {port: sim, baud: 115200, watchdog_ms: 200, dmx: {}}\n"
       "actuators:\n"
       "  - {channel: a, link: bus, address: 1}\n"
       "  - {channel: b, link: bus, address: 3, fine: true}\n",
       kWriteOnly},
      {"dynamixel", Carrier::serial,
       "name: fm-dynamixel\n" AVAR_FM_CHANNELS
       "links:\n  bus: {port: sim, baud: 1000000, watchdog_ms: 200, dynamixel: {readback: full, reply_timeout_ms: 5}}\n"
       "actuators:\n"
       "  - {channel: a, link: bus, id: 1, calibration: {min_position: 1024, max_position: 3072}}\n"
       "  - {channel: b, link: bus, id: 2, calibration: {min_position: 1024, max_position: 3072, reverse: true}}\n",
       kReadsReplies},
      {"dynamixel_pty", Carrier::pty,
       "name: fm-dynamixel-pty\n" AVAR_FM_CHANNELS
       "links:\n  bus: {port: sim, baud: 1000000, watchdog_ms: 200, dynamixel: {readback: full, reply_timeout_ms: 10}}\n"
       "actuators:\n"
       "  - {channel: a, link: bus, id: 1, calibration: {min_position: 1024, max_position: 3072}}\n"
       "  - {channel: b, link: bus, id: 2, calibration: {min_position: 1024, max_position: 3072, reverse: true}}\n",
       kPty},
      {"feetech", Carrier::serial,
       "name: fm-feetech\n" AVAR_FM_CHANNELS "links:\n  bus: {port: sim, baud: 1000000, watchdog_ms: 200, feetech: {series: sts, "
       "readback: full, reply_timeout_ms: 5}}\n"
       "actuators:\n"
       "  - {channel: a, link: bus, id: 1, calibration: {min_position: 1024, max_position: 3072}}\n"
       "  - {channel: b, link: bus, id: 2, calibration: {min_position: 1024, max_position: 3072, reverse: true}}\n",
       kReadsReplies},
      {"odrive_can", Carrier::serial,
       "name: fm-odrive\n" AVAR_FM_CHANNELS
       "links:\n  bus: {port: sim, baud: 1000000, watchdog_ms: 200, can: {heartbeat_ms: 50, heartbeat_timeout_ms: 200}}\n"
       "actuators:\n"
       "  - {channel: a, link: bus, protocol: odrive, node: 1, gear_ratio: 10}\n"
       "  - {channel: b, link: bus, protocol: odrive, node: 2, gear_ratio: 10, reverse: true}\n",
       kReadsReplies},
      {"cia402_can", Carrier::serial,
       "name: fm-cia402\n" AVAR_FM_CHANNELS
       "links:\n  bus: {port: sim, baud: 1000000, watchdog_ms: 200, can: {heartbeat_ms: 50, heartbeat_timeout_ms: 200}}\n"
       "actuators:\n"
       "  - {channel: a, link: bus, protocol: cia402, node: 5, gear_ratio: 50, counts_per_turn: 131072}\n"
       "  - {channel: b, link: bus, protocol: cia402, node: 6, gear_ratio: 30, counts_per_turn: 131072}\n",
       kReadsReplies},
      {"mit_can", Carrier::serial,
       "name: fm-mit\n" AVAR_FM_CHANNELS
       "links:\n  bus: {port: sim, baud: 1000000, watchdog_ms: 200, can: {heartbeat_ms: 50, heartbeat_timeout_ms: 200}}\n"
       "actuators:\n"
       "  - {channel: a, link: bus, protocol: mit, node: 16, gear_ratio: 6, model: mini-cheetah, kp: 40, kd: 1}\n"
       "  - {channel: b, link: bus, protocol: mit, node: 17, gear_ratio: 6, model: mini-cheetah, kp: 40, kd: 1}\n",
       kReadsReplies},
      {"artnet", Carrier::network,
       "name: fm-artnet\n" AVAR_FM_CHANNELS "links:\n  bus: {watchdog_ms: 200, artnet: {to: 127.0.0.1, universe: 1}}\n"
       "actuators:\n"
       "  - {channel: a, link: bus, address: 1}\n"
       "  - {channel: b, link: bus, address: 3, fine: true}\n",
       kNetwork},
      {"sacn", Carrier::network,
       "name: fm-sacn\n" AVAR_FM_CHANNELS
       "links:\n  bus: {watchdog_ms: 200, sacn: {universe: 7, to: 127.0.0.1, discovery: false}}\n"
       "actuators:\n"
       "  - {channel: a, link: bus, address: 1}\n"
       "  - {channel: b, link: bus, address: 3, fine: true}\n",
       kNetwork},
      {"gpio", Carrier::none,
       "name: fm-gpio\n"
       "rate_hz: 100\n"
       "channels:\n  a: {kind: digital}\n  b: {kind: digital}\n"
       "links:\n  bus: {port: sim, gpio: {}}\n"
       "actuators:\n"
       "  - {channel: a, link: bus, line: 17}\n"
       "  - {channel: b, link: bus, line: 27, active_low: true}\n",
       kNoWire},
      {"pca9685", Carrier::none,
       "name: fm-pca9685\n" AVAR_FM_CHANNELS "links:\n  bus: {port: sim, watchdog_ms: 200, pca9685: {address: 0x41}}\n"
       "actuators:\n"
       "  - {channel: a, link: bus, output: 0, calibration: {min_us: 1000, max_us: 2000}}\n"
       "  - {channel: b, link: bus, output: 9, calibration: {min_us: 1100, max_us: 1900}}\n",
       kI2c},
      {"avar_device", Carrier::serial,
       "name: fm-avar-device\n" AVAR_FM_CHANNELS
       "links:\n  bus: {port: sim, baud: 115200, watchdog_ms: 200, avar-device: {knot_ms: 50, lead_ms: 150}}\n"
       "actuators:\n"
       "  - {channel: a, link: bus, output: 1, calibration: {min_us: 1000, max_us: 2000}}\n"
       "  - {channel: b, link: bus, output: 0, calibration: {min_us: 1100, max_us: 1900, reverse: true}}\n",
       kWriteOnly},
      {"pwm", Carrier::none,
       "name: fm-pwm\n" AVAR_FM_CHANNELS "links:\n  bus: {port: sim, watchdog_ms: 200, pwm: {frequency: 50}}\n"
       "actuators:\n"
       "  - {channel: a, link: bus, pin: 9, calibration: {min_us: 1000, max_us: 2000}}\n"
       "  - {channel: b, link: bus, pin: 10, calibration: {min_us: 1100, max_us: 1900}}\n",
       kPwmChip},
  }};
  return cases;
}

#undef AVAR_FM_CHANNELS

}  // namespace avar::fault_matrix
