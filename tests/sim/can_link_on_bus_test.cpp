// Each CAN drive set end to end over the in-memory bus: the real CanLink and drive set against
// simulated drives on SimCanBus in wire timing, a moving curve streamed at 100 Hz, the simulated
// motors following it, every frame charged its worst-case bits.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <numbers>

#include "avar/firmware_iface/can_link.hpp"
#include "avar/firmware_iface/cia402_drives.hpp"
#include "avar/firmware_iface/mit_drives.hpp"
#include "avar/firmware_iface/odrive_drives.hpp"
#include "avar/sim/sim_can_bus.hpp"
#include "avar/sim/sim_can_transport.hpp"
#include "avar/sim/sim_cia402_drive.hpp"
#include "avar/sim/sim_mit_motor.hpp"
#include "avar/sim/sim_odrive_axis.hpp"

namespace avar::sim {
namespace {

constexpr int kOnBusDrives = 3;
constexpr double kOnBusTick_s = 0.01;

/// Channel units: degrees at the joint, ±90; each drive maps them to its own unit.
firmware_iface::LinearCalibration on_bus_calibration(double device_per_degree) {
  return {-90, 90, -90 * device_per_degree, 90 * device_per_degree, false, 0};
}

struct OnBusFigure {
  std::vector<std::unique_ptr<CanNode>> nodes;
  std::unique_ptr<firmware_iface::CanDrives> drives;
  std::function<double(std::size_t)> degrees;  ///< a drive's true position, channel units
};

OnBusFigure on_bus_odrives() {
  OnBusFigure f;
  firmware_iface::OdriveDrivesConfig config;
  config.tick_period_s = kOnBusTick_s;  // velocity feed-forward: the axis's loop does not lag
  std::vector<SimOdriveAxis*> axes;
  for (int i = 0; i < kOnBusDrives; ++i) {
    SimOdriveAxisConfig c;
    c.node = static_cast<std::uint8_t>(i + 1);
    auto axis = std::make_unique<SimOdriveAxis>(c);
    axes.push_back(axis.get());
    f.nodes.push_back(std::move(axis));
    firmware_iface::OdriveActuator a;
    a.channel = static_cast<std::size_t>(i);
    a.node = c.node;
    a.calibration = on_bus_calibration(1.0 / 360);  // one motor turn per joint turn
    config.actuators.push_back(a);
  }
  f.drives = std::make_unique<firmware_iface::OdriveDrives>(config);
  f.degrees = [axes](std::size_t i) { return axes[i]->position_turns() * 360; };
  return f;
}

OnBusFigure on_bus_cia402() {
  OnBusFigure f;
  firmware_iface::Cia402DrivesConfig config;
  std::vector<SimCia402Drive*> drives;
  for (int i = 0; i < kOnBusDrives; ++i) {
    SimCia402DriveConfig c;
    c.node = static_cast<std::uint8_t>(i + 1);
    c.counts_per_turn = 36000;
    auto drive = std::make_unique<SimCia402Drive>(c);
    drives.push_back(drive.get());
    f.nodes.push_back(std::move(drive));
    firmware_iface::Cia402Actuator a;
    a.channel = static_cast<std::size_t>(i);
    a.node = c.node;
    a.calibration = on_bus_calibration(100);
    config.actuators.push_back(a);
  }
  f.drives = std::make_unique<firmware_iface::Cia402Drives>(config);
  f.degrees = [drives](std::size_t i) { return drives[i]->position_counts() / 100; };
  return f;
}

OnBusFigure on_bus_mit() {
  OnBusFigure f;
  firmware_iface::MitDrivesConfig config;
  std::vector<SimMitMotor*> motors;
  for (int i = 0; i < kOnBusDrives; ++i) {
    SimMitMotorConfig c;
    c.id = static_cast<std::uint32_t>(i + 1);
    auto motor = std::make_unique<SimMitMotor>(c);
    motors.push_back(motor.get());
    f.nodes.push_back(std::move(motor));
    firmware_iface::MitActuator a;
    a.channel = static_cast<std::size_t>(i);
    a.node = c.id;
    a.kp = 40;
    a.kd = 1;
    a.calibration = on_bus_calibration(std::numbers::pi / 180);
    config.actuators.push_back(a);
  }
  f.drives = std::make_unique<firmware_iface::MitDrives>(config);
  f.degrees = [motors](std::size_t i) { return motors[i]->position() * 180 / std::numbers::pi; };
  return f;
}

/// Streams 3 s of a 0.5 Hz, ±30° sine (phase-shifted per drive) and returns the worst
/// difference between the command and the true position over the last 2 s, in degrees.
double on_bus_stream(OnBusFigure figure, double* load) {
  std::vector<CanNode*> raw;
  for (const auto& n : figure.nodes) raw.push_back(n.get());
  SimCanBus bus(SimCanBusConfig{}, raw);
  auto transport = std::make_unique<SimCanTransport>(bus);
  SimCanTransport* t = transport.get();
  std::vector<std::unique_ptr<firmware_iface::CanDrives>> sets;
  sets.push_back(std::move(figure.drives));
  firmware_iface::CanLink link(std::move(transport), std::move(sets), {});
  EXPECT_EQ(link.start(), Status::ok) << link.start_problem();
  std::vector<double> frame(kOnBusDrives, 0.0);
  double worst = 0;
  const double start = t->now_s();
  for (int tick = 0; tick < 300; ++tick) {
    // The command eases in from 0 over the first second.
    const double s = tick * kOnBusTick_s;
    const double ramp = std::min(1.0, s);
    for (int i = 0; i < kOnBusDrives; ++i) frame[i] = ramp * 30 * std::sin(std::numbers::pi * s + i);
    EXPECT_EQ(link.send(frame), Status::ok);
    // The rest of the tick passes on the bus: the drives move, their heartbeats wait for the
    // next send.
    bus.run_until(start + (tick + 1) * kOnBusTick_s);
    if (tick >= 100)
      for (int i = 0; i < kOnBusDrives; ++i) worst = std::max(worst, std::abs(figure.degrees(i) - frame[i]));
  }
  std::vector<firmware_iface::ChannelTelemetry> telemetry(kOnBusDrives);
  link.read_telemetry(telemetry);
  for (const auto& te : telemetry) EXPECT_EQ(te.faults, 0u);
  *load = t->statistics().load();
  return worst;
}

TEST(CanLinkOnBus, OdriveAxesFollowAStreamedCurve) {
  double load = 0;
  EXPECT_LT(on_bus_stream(on_bus_odrives(), &load), 3.0);
  EXPECT_GT(load, 0.0);
}

TEST(CanLinkOnBus, Cia402DrivesFollowAStreamedCurve) {
  double load = 0;
  EXPECT_LT(on_bus_stream(on_bus_cia402(), &load), 3.0);
  EXPECT_GT(load, 0.0);
}

TEST(CanLinkOnBus, MitMotorsFollowAStreamedCurve) {
  double load = 0;
  EXPECT_LT(on_bus_stream(on_bus_mit(), &load), 3.0);
  EXPECT_GT(load, 0.0);
}

}  // namespace
}  // namespace avar::sim
