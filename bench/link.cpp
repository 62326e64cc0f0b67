// Link efficiency: for each bus protocol, 16 and 32 actuators, with and without read-back, the
// bytes the real driver puts on the wire per tick and the highest tick rate the bus sustains at
// its baud rate, set against the theoretical limit from the protocol's minimum packet sizes
// (../shared/protocols/README.md). The driver runs unmodified over SimWire, which charges every
// byte its 10 bit times and lets the simulated device answer: achieved = ticks / simulated
// seconds. Also the driver's own CPU cost per exchange (encode + decode), on the side.
//
// Prints one line per case:
//   link,<protocol>,actuators=<n>,baud=<b>,readback=<0|1>,achieved_hz=<x>,limit_hz=<y>
#include <array>
#include <chrono>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "avar/firmware_iface/dynamixel_codec.hpp"
#include "avar/firmware_iface/dynamixel_link.hpp"
#include "avar/firmware_iface/feetech_link.hpp"
#include "avar/sim/sim_dynamixel.hpp"
#include "avar/sim/sim_feetech.hpp"
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
  return 0;
}
