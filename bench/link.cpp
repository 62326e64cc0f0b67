// Link efficiency: for each bus protocol, 16 and 32 actuators, with and without read-back, the
// bytes the real driver puts on the wire per tick and the highest tick rate the bus sustains at
// its baud rate, set against the theoretical limit from the protocol's minimum packet sizes
// (../shared/protocols/README.md). The driver runs unmodified over SimWire, which charges every
// byte its 10 bit times and lets the simulated device answer: achieved = ticks / simulated
// seconds. Also the driver's own CPU cost per exchange (encode + decode), on the side.
//
// CAN drives (ODrive, CiA 402, MIT) run the same way: 16 drives at 1 Mbit/s, the real CanLink
// and drive set over the in-memory bus (SimCanTransport), which charges every frame its
// worst-case bits (stuff bits included, can_frame_bits); the limit is the notes' arithmetic for
// one tick's frames, less the drives' heartbeats. Over SLCAN (slcan-<drive>) the same link runs
// through a simulated adapter on a simulated serial wire, whose byte rate is then the limit.
//
// Prints one line per case (for CAN rows, baud is the bus bitrate; for SLCAN rows, the serial
// rate):
//   link,<protocol>,actuators=<n>,baud=<b>,readback=<0|1>,achieved_hz=<x>,limit_hz=<y>
#include <array>
#include <chrono>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "avar/firmware_iface/can_link.hpp"
#include "avar/firmware_iface/cia402_drives.hpp"
#include "avar/firmware_iface/dynamixel_codec.hpp"
#include "avar/firmware_iface/dynamixel_link.hpp"
#include "avar/firmware_iface/feetech_link.hpp"
#include "avar/firmware_iface/mit_drives.hpp"
#include "avar/firmware_iface/odrive_drives.hpp"
#include "avar/firmware_iface/slcan_transport.hpp"
#include "avar/sim/sim_can_bus.hpp"
#include "avar/sim/sim_can_transport.hpp"
#include "avar/sim/sim_cia402_drive.hpp"
#include "avar/sim/sim_dynamixel.hpp"
#include "avar/sim/sim_feetech.hpp"
#include "avar/sim/sim_mit_motor.hpp"
#include "avar/sim/sim_odrive_axis.hpp"
#include "avar/sim/sim_slcan_adapter.hpp"
#include "avar/sim/sim_wire.hpp"

namespace {

using namespace avar;

constexpr int kTicks = 2000;

struct Case {
  std::string protocol;
  int actuators;
  int baud;
  bool readback;
  /// Bytes of one full update at the protocol's minimum packet sizes.
  double minimum_bytes;
};

struct Measured {
  double achieved_hz;
  double bytes_per_tick;
  double cpu_us_per_tick;
};

/// Runs kTicks sends of a moving frame through `link` over `wire`.
Measured run(firmware_iface::ActuatorLink& link, sim::SimWire& wire, int actuators) {
  if (link.start() != Status::ok) {
    std::fprintf(stderr, "link did not start: %s\n", link.start_problem().c_str());
    std::exit(1);
  }
  std::vector<double> frame(static_cast<std::size_t>(actuators), 0.0);
  const double t0 = wire.now_s();
  const std::uint64_t b0 = wire.bytes_written() + wire.bytes_read();
  const auto c0 = std::chrono::steady_clock::now();
  for (int tick = 0; tick < kTicks; ++tick) {
    for (std::size_t i = 0; i < frame.size(); ++i) frame[i] = 40.0 * ((tick + static_cast<int>(i)) % 100) / 100.0 - 20.0;
    if (link.send(frame) != Status::ok) {
      std::fprintf(stderr, "send failed at tick %d\n", tick);
      std::exit(1);
    }
  }
  const double cpu_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - c0).count();
  const double sim_s = wire.now_s() - t0;
  const double bytes = static_cast<double>(wire.bytes_written() + wire.bytes_read() - b0);
  return {kTicks / sim_s, bytes / kTicks, cpu_s / kTicks * 1e6};
}

Measured dynamixel(const Case& c) {
  sim::SimDynamixelConfig bus;
  firmware_iface::DynamixelLinkConfig config;
  config.readback = c.readback ? firmware_iface::DynamixelReadback::position : firmware_iface::DynamixelReadback::none;
  for (int i = 0; i < c.actuators; ++i) {
    sim::SimDynamixelServo s;
    s.id = static_cast<std::uint8_t>(i + 1);
    bus.servos.push_back(s);
    firmware_iface::DynamixelActuator a;
    a.channel = static_cast<std::size_t>(i);
    a.id = s.id;
    a.calibration = {-90, 90, 1024, 3072, false, 0};
    config.actuators.push_back(a);
  }
  sim::SimDynamixel device(bus);
  // Return Delay Time 0, as the protocol notes advise for fast polling.
  for (int i = 0; i < c.actuators; ++i) {
    std::array<std::uint8_t, 32> packet{};
    const std::array<std::uint8_t, 1> zero{0};
    device.receive(std::span(packet.data(), firmware_iface::dynamixel::encode_write(packet, static_cast<std::uint8_t>(i + 1),
                                                                                     firmware_iface::dynamixel::kReturnDelayTime, zero)));
    std::array<std::uint8_t, 64> drain{};
    while (device.take_replies(drain) > 0) {
    }
  }
  sim::SimWire wire(device, c.baud);
  firmware_iface::DynamixelLink link(wire, config);
  return run(link, wire, c.actuators);
}

Measured feetech(const Case& c) {
  sim::SimFeetechConfig bus;
  bus.baud = c.baud;
  firmware_iface::FeetechLinkConfig config;
  config.baud = c.baud;
  config.readback = c.readback ? firmware_iface::FeetechReadback::position : firmware_iface::FeetechReadback::none;
  for (int i = 0; i < c.actuators; ++i) {
    sim::SimFeetechServo s;
    s.id = static_cast<std::uint8_t>(i + 1);
    bus.servos.push_back(s);
    firmware_iface::FeetechActuator a;
    a.channel = static_cast<std::size_t>(i);
    a.id = s.id;
    a.calibration = {-90, 90, 1024, 3072, false, 0};
    config.actuators.push_back(a);
  }
  sim::SimFeetech device(bus);
  sim::SimWire wire(device, c.baud);
  firmware_iface::FeetechLink link(wire, config);
  return run(link, wire, c.actuators);
}

// ---- CAN -------------------------------------------------------------------------------------

constexpr int kCanDrives = 16;
constexpr int kCanBitrate = 1'000'000;
constexpr double kHeartbeat_s = 0.1;

/// Simulated drives of one protocol, and the drive set that drives them.
struct CanFigure {
  std::vector<std::unique_ptr<sim::CanNode>> nodes;
  std::unique_ptr<firmware_iface::CanDrives> drives;
  /// Worst-case bits of one tick's frames (commands, requests, replies) and of the heartbeats
  /// per second, by the notes' arithmetic.
  double tick_bits = 0;
  double heartbeat_bits_per_s = 0;
  /// SLCAN text of one tick's frames (standard frames: `tIIIL`, two hex digits per byte, CR).
  double tick_slcan_bytes = 0;
  std::vector<sim::CanNode*> raw() const {
    std::vector<sim::CanNode*> out;
    for (const auto& n : nodes) out.push_back(n.get());
    return out;
  }
};

/// Characters of one standard frame's SLCAN line (RTR lines carry no data).
constexpr double slcan_line(int data_bytes) { return 1 + 3 + 1 + 2.0 * data_bytes + 1; }

firmware_iface::LinearCalibration can_calibration(double device_span) { return {-20, 20, -device_span, device_span, false, 0}; }

CanFigure odrive_figure() {
  CanFigure f;
  firmware_iface::OdriveDrivesConfig config;
  for (int i = 0; i < kCanDrives; ++i) {
    sim::SimOdriveAxisConfig axis;
    axis.node = static_cast<std::uint8_t>(i + 1);
    axis.heartbeat_period_s = kHeartbeat_s;
    f.nodes.push_back(std::make_unique<sim::SimOdriveAxis>(axis));
    firmware_iface::OdriveActuator a;
    a.channel = static_cast<std::size_t>(i);
    a.node = axis.node;
    a.calibration = can_calibration(0.5);
    a.velocity_limit = 50;
    config.actuators.push_back(a);
  }
  f.drives = std::make_unique<firmware_iface::OdriveDrives>(config);
  // Set Input Pos (8 bytes), an RTR (no data) and the encoder estimate (8 bytes) per axis.
  f.tick_bits = kCanDrives * (2.0 * firmware_iface::can_frame_bits(8) + firmware_iface::can_frame_bits(0));
  f.heartbeat_bits_per_s = kCanDrives * firmware_iface::can_frame_bits(8) / kHeartbeat_s;
  f.tick_slcan_bytes = kCanDrives * (2 * slcan_line(8) + slcan_line(0));
  return f;
}

CanFigure cia402_figure() {
  CanFigure f;
  firmware_iface::Cia402DrivesConfig config;
  config.heartbeat_ms = static_cast<std::uint16_t>(kHeartbeat_s * 1000);
  for (int i = 0; i < kCanDrives; ++i) {
    sim::SimCia402DriveConfig drive;
    drive.node = static_cast<std::uint8_t>(i + 1);
    f.nodes.push_back(std::make_unique<sim::SimCia402Drive>(drive));
    firmware_iface::Cia402Actuator a;
    a.channel = static_cast<std::size_t>(i);
    a.node = drive.node;
    a.calibration = can_calibration(20000);
    config.actuators.push_back(a);
  }
  f.drives = std::make_unique<firmware_iface::Cia402Drives>(config);
  // One SYNC, an RPDO (controlword + target, 6 bytes) and a TPDO (statusword + position, 6 bytes)
  // per drive.
  f.tick_bits = firmware_iface::can_frame_bits(0) + kCanDrives * 2.0 * firmware_iface::can_frame_bits(6);
  f.heartbeat_bits_per_s = kCanDrives * firmware_iface::can_frame_bits(1) / kHeartbeat_s;
  f.tick_slcan_bytes = slcan_line(0) + kCanDrives * 2 * slcan_line(6);
  return f;
}

CanFigure mit_figure() {
  CanFigure f;
  firmware_iface::MitDrivesConfig config;
  for (int i = 0; i < kCanDrives; ++i) {
    sim::SimMitMotorConfig motor;
    motor.id = static_cast<std::uint32_t>(i + 1);
    f.nodes.push_back(std::make_unique<sim::SimMitMotor>(motor));
    firmware_iface::MitActuator a;
    a.channel = static_cast<std::size_t>(i);
    a.node = motor.id;
    a.calibration = can_calibration(1.0);
    config.actuators.push_back(a);
  }
  f.drives = std::make_unique<firmware_iface::MitDrives>(config);
  // An 8-byte command and its 6-byte reply per motor; no heartbeat.
  f.tick_bits = kCanDrives * (firmware_iface::can_frame_bits(8) + 1.0 * firmware_iface::can_frame_bits(6));
  f.tick_slcan_bytes = kCanDrives * (slcan_line(8) + slcan_line(6));
  return f;
}

struct CanMeasured {
  double achieved_hz;
  double frames_per_tick;
  double bits_per_tick;
  double bus_load;
  double bytes_per_tick;  ///< on the serial link (SLCAN rows)
};

/// Starts `link`, then times kTicks sends of a moving frame on `seconds()`'s clock.
template <class Seconds>
CanMeasured run_can(firmware_iface::CanLink& link, Seconds seconds) {
  if (link.start() != Status::ok) {
    std::fprintf(stderr, "CAN link did not start: %s\n", link.start_problem().c_str());
    std::exit(1);
  }
  std::vector<double> frame(kCanDrives, 0.0);
  const double t0 = seconds();
  const firmware_iface::CanLinkStats s0 = link.stats();
  const firmware_iface::LinkCounters k0 = link.counters();
  for (int tick = 0; tick < kTicks; ++tick) {
    for (std::size_t i = 0; i < frame.size(); ++i) frame[i] = 0.2 * ((tick + static_cast<int>(i)) % 100) - 10.0;
    if (link.send(frame) != Status::ok) {
      std::fprintf(stderr, "CAN send failed at tick %d\n", tick);
      std::exit(1);
    }
  }
  const double elapsed = seconds() - t0;
  const firmware_iface::CanLinkStats& s = link.stats();
  const firmware_iface::LinkCounters k = link.counters();
  const double frames = static_cast<double>(s.frames_sent - s0.frames_sent + s.frames_taken - s0.frames_taken);
  const double bits = static_cast<double>(s.bits_sent - s0.bits_sent + s.bits_received - s0.bits_received);
  const double bytes = static_cast<double>(k.bytes_sent - k0.bytes_sent + k.bytes_received - k0.bytes_received);
  return {kTicks / elapsed, frames / kTicks, bits / kTicks, bits / elapsed / kCanBitrate, bytes / kTicks};
}

/// The drive set over the in-memory bus at 1 Mbit/s.
CanMeasured can_on_bus(CanFigure figure) {
  sim::SimCanBusConfig bus_config;
  bus_config.bitrate = kCanBitrate;
  sim::SimCanBus bus(bus_config, figure.raw());
  auto transport = std::make_unique<sim::SimCanTransport>(bus);
  sim::SimCanTransport* t = transport.get();
  std::vector<std::unique_ptr<firmware_iface::CanDrives>> sets;
  sets.push_back(std::move(figure.drives));
  firmware_iface::CanLink link(std::move(transport), std::move(sets), {});
  return run_can(link, [t] { return t->now_s(); });
}

/// The drive set through a simulated SLCAN adapter on a serial wire at `baud`.
CanMeasured can_over_slcan(CanFigure figure, int baud) {
  sim::SimSlcanAdapter adapter(sim::SimSlcanConfig{.bus_bitrate = kCanBitrate}, figure.raw());
  sim::SimWire wire(adapter, baud);
  auto transport = std::make_unique<firmware_iface::SlcanTransport>(wire, kCanBitrate);
  std::vector<std::unique_ptr<firmware_iface::CanDrives>> sets;
  sets.push_back(std::move(figure.drives));
  firmware_iface::CanLink link(std::move(transport), std::move(sets), {});
  return run_can(link, [&wire] { return wire.now_s(); });
}

void can_rows() {
  std::printf("# CAN drives: %d per bus at %d bit/s, %d ticks per case through CanLink and the real drive sets\n", kCanDrives,
              kCanBitrate, kTicks);
  const struct {
    const char* name;
    CanFigure (*make)();
  } drives[] = {{"odrive", odrive_figure}, {"cia402", cia402_figure}, {"mit", mit_figure}};
  for (const auto& d : drives) {
    const CanFigure shape = d.make();
    const double limit_hz = (kCanBitrate - shape.heartbeat_bits_per_s) / shape.tick_bits;
    const CanMeasured m = can_on_bus(d.make());
    std::printf("link,%s,actuators=%d,baud=%d,readback=1,achieved_hz=%.1f,limit_hz=%.1f\n", d.name, kCanDrives, kCanBitrate,
                m.achieved_hz, limit_hz);
    std::printf(
        "#   %.1f frames and %.0f bits per tick (notes' arithmetic %.0f + heartbeats), bus load %.1f%%, %.1f%% of the limit\n",
        m.frames_per_tick, m.bits_per_tick, shape.tick_bits, 100 * m.bus_load, 100.0 * m.achieved_hz / limit_hz);
  }
  for (const auto& d : drives)
    // Serial rates at which the SLCAN text, not the CAN bus, is the bottleneck (a UART adapter;
    // the simulated adapter delivers frames on its bus at once, so it cannot show a CAN limit).
    for (int baud : {115200, 1'000'000}) {
      const CanFigure shape = d.make();
      const double can_limit_hz = (kCanBitrate - shape.heartbeat_bits_per_s) / shape.tick_bits;
      const CanMeasured m = can_over_slcan(d.make(), baud);
      // The serial link's limit: one tick's frames as SLCAN text, at 10 bit times per byte (the
      // adapter's transmit acknowledgements and the heartbeats' lines come on top).
      const double serial_limit_hz = baud / (10.0 * shape.tick_slcan_bytes);
      std::printf("link,slcan-%s,actuators=%d,baud=%d,readback=1,achieved_hz=%.1f,limit_hz=%.1f\n", d.name, kCanDrives, baud,
                  m.achieved_hz, serial_limit_hz);
      std::printf(
          "#   %.0f bytes of SLCAN text per tick (frames alone %.0f): %.1f%% of the serial limit; the CAN bus behind it allows "
          "%.1f Hz\n",
          m.bytes_per_tick, shape.tick_slcan_bytes, 100.0 * m.achieved_hz / serial_limit_hz, can_limit_hz);
    }
}

}  // namespace

int main() {
  std::printf("# bus link efficiency: %d ticks per case through the real drivers on a simulated wire (8N1)\n", kTicks);
  std::vector<std::pair<Case, std::function<Measured(const Case&)>>> cases;
  for (int n : {16, 32})
    for (bool readback : {false, true}) {
      // DYNAMIXEL 2.0: Sync Write of 4-byte goals = 14 + 5n; Sync Read of 4-byte positions =
      // request 14 + n, replies 15 each.
      const double write = 14 + 5.0 * n;
      const double read = readback ? (14 + n) + 15.0 * n : 0;
      cases.push_back({{"dynamixel", n, 1'000'000, readback, write + read}, dynamixel});
    }
  for (int n : {16, 32})
    for (bool readback : {false, true}) {
      // Feetech STS: Sync Write of 2-byte goals = 8 + 3n; Sync Read of 2-byte positions =
      // request 8 + n, replies 8 each.
      const double write = 8 + 3.0 * n;
      const double read = readback ? (8 + n) + 8.0 * n : 0;
      cases.push_back({{"feetech", n, 1'000'000, readback, write + read}, feetech});
    }
  for (const auto& [c, measure] : cases) {
    const Measured m = measure(c);
    const double limit_hz = 1.0 / firmware_iface::wire_seconds(static_cast<std::size_t>(c.minimum_bytes), c.baud);
    std::printf("link,%s,actuators=%d,baud=%d,readback=%d,achieved_hz=%.1f,limit_hz=%.1f\n", c.protocol.c_str(),
                c.actuators, c.baud, c.readback ? 1 : 0, m.achieved_hz, limit_hz);
    std::printf("#   %.1f bytes per tick (minimum %.0f), %.1f%% of the limit, driver + simulated device CPU %.2f us per tick\n",
                m.bytes_per_tick, c.minimum_bytes, 100.0 * m.achieved_hz / limit_hz, m.cpu_us_per_tick);
  }
  can_rows();
  return 0;
}
