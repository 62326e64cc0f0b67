// The simulated Maestro on USB answers the vendor requests with the SDK's exact layouts and
// stalls what the device refuses; the real USB driver (MaestroUsbLink) runs against it at the
// control-transfer seam: limits at start, one Set Target per actuator and one read per tick,
// telemetry, release, a reconnect after an unplug, and the silence budget.
#include "avar/sim/sim_maestro_usb.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "avar/firmware_iface/maestro_codec.hpp"
#include "avar/firmware_iface/maestro_usb_codec.hpp"
#include "avar/firmware_iface/maestro_usb_link.hpp"
#include "avar/sim/faulty_usb_device.hpp"
#include "avar/sim/usb_device_host.hpp"

namespace avar::sim {
namespace {

namespace usb = firmware_iface::maestro_usb;
using firmware_iface::UsbSetup;

SimMaestroConfig usb_sim_config(int channels) {
  SimMaestroConfig c;
  c.channel_count = channels;
  c.log_limit = 1000;
  return c;
}

/// One transfer with no data stage.
Status usb_out(SimMaestroUsb& d, const UsbSetup& setup) {
  std::size_t got = 0;
  return d.control(setup, {}, &got);
}

/// One in-transfer; the reply, or empty when stalled.
std::vector<std::uint8_t> usb_in(SimMaestroUsb& d, const UsbSetup& setup) {
  std::array<std::uint8_t, 256> data{};
  std::size_t got = 0;
  if (d.control(setup, data, &got) != Status::ok) return {};
  return {data.begin(), data.begin() + static_cast<long>(got)};
}

TEST(SimMaestroUsb, SetTargetAndReadItBackInTheMiniLayout) {
  SimMaestroUsb d(usb_sim_config(12));
  EXPECT_EQ(d.product_id(), 0x008A);
  ASSERT_EQ(usb_out(d, usb::set_target(3, 6000)), Status::ok);
  ASSERT_EQ(usb_out(d, usb::set_speed(3, 140)), Status::ok);
  ASSERT_EQ(usb_out(d, usb::set_acceleration(3, 4)), Status::ok);
  EXPECT_EQ(d.target(3), 6000);
  EXPECT_EQ(d.speed(3), 140);
  EXPECT_EQ(d.acceleration(3), 4);
  const std::vector<std::uint8_t> reply = usb_in(d, usb::get_servo_settings(12));
  ASSERT_EQ(reply.size(), 84u);
  // Channel 3's record at 21: position 6000 (the first pulse is the target), target 6000,
  // speed 140, acceleration 4.
  EXPECT_EQ(std::vector<std::uint8_t>(reply.begin() + 21, reply.begin() + 28),
            (std::vector<std::uint8_t>{0x70, 0x17, 0x70, 0x17, 0x8C, 0x00, 0x04}));
  // Targets are clamped to the channel's range (992..2000 µs by default).
  ASSERT_EQ(usb_out(d, usb::set_target(4, 9000)), Status::ok);
  EXPECT_EQ(d.target(4), 8000);
}

TEST(SimMaestroUsb, MicroMaestroAnswersItsVariablesWithTheServoRecords) {
  SimMaestroUsb d(usb_sim_config(6));
  EXPECT_EQ(d.product_id(), 0x0089);
  ASSERT_EQ(usb_out(d, usb::set_target(5, 4000)), Status::ok);
  d.raise(firmware_iface::maestro::kSerialTimeout);  // errors send the channels home: off
  ASSERT_EQ(usb_out(d, usb::set_target(5, 4000)), Status::ok);
  const std::vector<std::uint8_t> reply = usb_in(d, usb::get_variables(6));
  ASSERT_EQ(reply.size(), 140u);
  std::uint16_t errors = 0;
  ASSERT_TRUE(usb::decode_errors(reply, &errors));
  EXPECT_EQ(errors, firmware_iface::maestro::kSerialTimeout);
  EXPECT_EQ(reply[96], 1);  // scriptDone: no script runs
  usb::ServoStatus s;
  ASSERT_TRUE(usb::decode_servo_status(reply, 6, 5, &s));
  EXPECT_EQ(s, (usb::ServoStatus{4000, 4000, 0, 0}));
  // Clear Errors clears; Get Variables alone does not.
  EXPECT_EQ(d.errors(), firmware_iface::maestro::kSerialTimeout);
  ASSERT_EQ(usb_out(d, usb::clear_errors()), Status::ok);
  EXPECT_EQ(d.errors(), 0);
}

TEST(SimMaestroUsb, StallsWhatTheDeviceRefuses) {
  SimMaestroUsb d(usb_sim_config(6));
  EXPECT_TRUE(usb_in(d, usb::get_servo_settings(6)).empty());                    // no such request on the Micro
  EXPECT_EQ(usb_out(d, usb::set_target(6, 6000)), Status::bad_data);             // no channel 6
  EXPECT_EQ(usb_out(d, {0x40, 0x7F, 0, 0, 0}), Status::bad_data);                // unknown request
  EXPECT_EQ(usb_out(d, {0x41, usb::kSetTarget, 6000, 0, 0}), Status::bad_data);  // interface recipient
  EXPECT_TRUE(usb_in(d, {0xC0, usb::kSetTarget, 6000, 0, 0}).empty());           // an out request asked as in
  EXPECT_EQ(d.stalls(), 5u);
  EXPECT_EQ(d.target(0), 0);
  // A short wLength gets the first bytes of the reply.
  EXPECT_EQ(usb_in(d, {0xC0, usb::kGetVariables, 0, 0, 4}).size(), 4u);
}

// ---- the driver against the simulated device -------------------------------------------------

firmware_iface::MaestroUsbLinkConfig usb_link_config(int channels) {
  firmware_iface::MaestroUsbLinkConfig config;
  config.channel_count = channels;
  firmware_iface::LinearCalibration cal;  // channel 0..1 -> 1000..2000 µs
  // Rig channel 1 on device channel 4 with limits; rig channel 0 on device channel 2 without.
  config.actuators.push_back({1, 4, cal, 500.0, 2500.0});
  config.actuators.push_back({0, 2, cal, std::nullopt, std::nullopt});
  return config;
}

struct UsbRig {
  explicit UsbRig(int channels) : device(usb_sim_config(channels), "00012345"), host(device, "USB (serial 00012345)") {}
  SimMaestroUsb device;
  UsbDeviceHost host;
};

TEST(MaestroUsbLinkOnSimulator, StartClearsErrorsAndSendsTheLimits) {
  UsbRig r(12);
  r.device.raise(firmware_iface::maestro::kSerialSignalError);
  firmware_iface::MaestroUsbLink link(r.host.connect(), usb_link_config(12));
  EXPECT_EQ(link.describe(), "Maestro (12 channels) on USB (serial 00012345)");
  ASSERT_EQ(link.start(), Status::ok);
  EXPECT_EQ(link.start_problem(), "errors latched before start, cleared: serial signal error");
  EXPECT_EQ(r.device.errors(), 0);
  // 500 µs/s = 20 units of 25 µs/s; 2500 µs/s² = 8 units of 312.5 µs/s²; none: 0 (unlimited).
  const std::vector<UsbSetup> expected{usb::get_variables(12),      usb::clear_errors(),  usb::set_speed(4, 20),
                                       usb::set_acceleration(4, 8), usb::set_speed(2, 0), usb::set_acceleration(2, 0)};
  EXPECT_EQ(std::vector<UsbSetup>(r.device.log().begin(), r.device.log().end()), expected);
  EXPECT_EQ(r.device.speed(4), 20);
  EXPECT_EQ(r.device.acceleration(4), 8);
}

TEST(MaestroUsbLinkOnSimulator, EachTickSetsEveryTargetThenReadsThePulsesAsTelemetry) {
  UsbRig r(18);
  firmware_iface::MaestroUsbLink link(r.host.connect(), usb_link_config(18));
  ASSERT_EQ(link.start(), Status::ok);
  const std::size_t before = r.device.log().size();
  const std::vector<double> frame{0.25, 0.75};  // rig channel 0 -> 1250 µs, 1 -> 1750 µs
  ASSERT_EQ(link.send(frame), Status::ok);
  const std::vector<UsbSetup> tick(r.device.log().begin() + static_cast<long>(before), r.device.log().end());
  EXPECT_EQ(tick, (std::vector<UsbSetup>{usb::set_target(4, 7000), usb::set_target(2, 5000), usb::get_servo_settings(18)}));
  std::vector<firmware_iface::ChannelTelemetry> telemetry(2);
  link.read_telemetry(telemetry);
  // From no pulses the first pulse is the target itself.
  EXPECT_NEAR(telemetry[0].position, 0.25, 1e-9);
  EXPECT_NEAR(telemetry[1].position, 0.75, 1e-9);
  EXPECT_EQ(telemetry[1].updates, 1u);

  // Channel 1 toward 2000 µs under its limits, from rest at 2500 µs/s² (the 500 µs/s speed
  // limit is 0.2 s away): after 0.1 s its pulse is ½·2500·0.1² = 12.5 µs on, at 1762.5 µs.
  ASSERT_EQ(link.send(std::vector<double>{0.25, 1.0}), Status::ok);
  r.host.with_device([](UsbControlDevice& d) { d.advance(0.1); });
  ASSERT_EQ(link.send(std::vector<double>{0.25, 1.0}), Status::ok);
  link.read_telemetry(telemetry);
  EXPECT_NEAR(telemetry[1].position, 0.7625, 1e-3);
  std::vector<double> positions(2, -1);
  std::array<bool, 2> known{};
  ASSERT_EQ(link.read_positions(positions, known), Status::ok);
  EXPECT_TRUE(known[0] && known[1]);
  EXPECT_NEAR(positions[1], 0.7625, 1e-3);

  const firmware_iface::LinkCounters k = link.counters();
  EXPECT_EQ(k.exchanges, 3u);
  EXPECT_EQ(k.replies, 1u + 3u + 1u);  // start's variables, three ticks, read_positions
  EXPECT_EQ(k.bytes_received, 8u + 4 * 126u);
}

TEST(MaestroUsbLinkOnSimulator, ReleasedActuatorsGetNoPulses) {
  UsbRig r(6);
  firmware_iface::MaestroUsbLink link(r.host.connect(), usb_link_config(6));
  ASSERT_EQ(link.start(), Status::ok);
  ASSERT_EQ(link.send(std::vector<double>{0.5, 0.5}), Status::ok);
  link.release_channel(1);
  ASSERT_EQ(link.send(std::vector<double>{0.5, 0.5}), Status::ok);
  EXPECT_EQ(r.device.target(4), 0);
  EXPECT_EQ(r.device.target(2), 6000);
  std::vector<firmware_iface::ChannelTelemetry> telemetry(2);
  link.read_telemetry(telemetry);
  EXPECT_TRUE(std::isnan(telemetry[1].position));  // no pulse: unknown, not old
  ASSERT_EQ(link.release(), Status::ok);
  EXPECT_EQ(r.device.target(2), 0);
}

TEST(MaestroUsbLinkOnSimulator, AnUnpluggedMaestroIsReopenedAndGetsItsLimitsAgain) {
  UsbRig r(12);
  firmware_iface::MaestroUsbLink link(r.host.connect(), usb_link_config(12));
  ASSERT_EQ(link.start(), Status::ok);
  const std::vector<double> frame{0.5, 0.5};
  ASSERT_EQ(link.send(frame), Status::ok);
  r.host.set_plugged(false);
  EXPECT_EQ(link.send(frame), Status::io_error);
  std::vector<firmware_iface::ChannelTelemetry> telemetry(2);
  link.read_telemetry(telemetry);
  EXPECT_TRUE(std::isnan(telemetry[0].position));
  // The device comes back having forgotten its limits (a power cycle).
  r.host.with_device([](UsbControlDevice& d) {
    std::size_t got = 0;
    ASSERT_EQ(d.control(usb::set_speed(4, 0), {}, &got), Status::ok);
  });
  EXPECT_EQ(r.device.speed(4), 0);
  r.host.set_plugged(true);
  int tries = 0;
  while (link.send(frame) != Status::ok && tries < 20) ++tries;
  EXPECT_LT(tries, 20);
  EXPECT_EQ(link.counters().reconnects, 1u);
  EXPECT_EQ(r.device.speed(4), 20);
  EXPECT_EQ(r.device.target(4), 6000);
}

TEST(MaestroUsbLinkOnSimulator, ASilentMaestroCostsTelemetryUntilItsSilenceBudgetRunsOut) {
  SimMaestroUsb device(usb_sim_config(12), "00012345");
  FaultyUsbDevice faulty(device, FaultPlan{}, 0.1);
  UsbDeviceHost host(faulty, "USB (serial 00012345)");
  firmware_iface::MaestroUsbLinkConfig config = usb_link_config(12);
  config.silent_ticks = 3;
  firmware_iface::MaestroUsbLink link(host.connect(), config);
  ASSERT_EQ(link.start(), Status::ok);
  const std::vector<double> frame{0.5, 0.5};
  ASSERT_EQ(link.send(frame), Status::ok);
  std::vector<firmware_iface::ChannelTelemetry> telemetry(2);

  FaultPlan silent;
  silent.silent = true;
  faulty.set_plan(silent);
  // Two failed ticks are within the budget: ok, but the telemetry is unknown, not old.
  for (int tick = 0; tick < 2; ++tick) {
    EXPECT_EQ(link.send(frame), Status::ok) << "tick " << tick;
    link.read_telemetry(telemetry);
    EXPECT_TRUE(std::isnan(telemetry[0].position) && std::isnan(telemetry[1].position));
  }
  EXPECT_EQ(link.send(frame), Status::timeout);  // the third in a row: the watchdog's fault
  EXPECT_EQ(link.send(frame), Status::timeout);  // and it stays one while the Maestro is silent
  EXPECT_EQ(link.counters().timeouts, faulty.counts().replies_silenced + faulty.counts().commands_dropped);
  EXPECT_GE(link.counters().timeouts, 4u);

  // Answers again: whole ticks empty the count, so a later silence gets the whole budget.
  faulty.set_plan(FaultPlan{});
  ASSERT_EQ(link.send(frame), Status::ok);
  link.read_telemetry(telemetry);
  EXPECT_NEAR(telemetry[0].position, 0.5, 1e-9);
  faulty.set_plan(silent);
  EXPECT_EQ(link.send(frame), Status::ok);
  EXPECT_EQ(link.send(frame), Status::ok);
  EXPECT_EQ(link.send(frame), Status::timeout);
}

TEST(MaestroUsbLinkOnSimulator, AnUnpluggedMaestroFailsTheLinkAtOnceWhateverTheBudget) {
  UsbRig r(12);
  firmware_iface::MaestroUsbLinkConfig config = usb_link_config(12);
  config.silent_ticks = 50;
  firmware_iface::MaestroUsbLink link(r.host.connect(), config);
  ASSERT_EQ(link.start(), Status::ok);
  r.host.set_plugged(false);
  EXPECT_EQ(link.send(std::vector<double>{0.5, 0.5}), Status::io_error);
}

TEST(MaestroUsbLinkOnSimulator, RefusesAnEmptySilenceBudget) {
  UsbRig r(12);
  firmware_iface::MaestroUsbLinkConfig config = usb_link_config(12);
  config.silent_ticks = 0;
  EXPECT_THROW(firmware_iface::MaestroUsbLink(r.host.connect(), config), std::invalid_argument);
}

}  // namespace
}  // namespace avar::sim
