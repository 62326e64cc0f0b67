// A figure whose Maestro is on native USB, assembled from the example rig and simulated at the
// control-transfer seam: the real USB driver plays a show through FigureLinks exactly as the
// serial driver plays it through a pseudo-terminal, and a real link that finds no Maestro says
// what is missing at the rig's usb setting.
#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "avar/assembly/figure_links.hpp"
#include "avar/assembly/maestro_protocol.hpp"
#include "avar/config/rig_file.hpp"
#include "avar/config/show_check.hpp"
#include "avar/config/show_file.hpp"
#include "avar/sim/sim_maestro_usb.hpp"
#include "../support/stepped_figure_run.hpp"

namespace avar {
namespace {

class UsbFigureUnwatched final : public control::TickObserver {
 public:
  void after_tick(std::uint64_t, double, double, double, control::Controller&) override {}
};

/// Plays hello-head on a rig and returns every channel's true position at the end.
std::vector<double> usb_figure_play(const rig::Rig& rig, assembly::FigureLinks& figure) {
  const playback::Show show = config::load_show_file(AVAR_SOURCE_DIR "/examples/shows/hello-head.yaml");
  EXPECT_TRUE(config::check_show_against_rig(show, rig).ok());
  for (firmware_iface::ActuatorLink* link : figure.links()) EXPECT_EQ(link->start(), Status::ok);
  testing::SteppedFigureRun play(rig, show, figure);
  UsbFigureUnwatched nobody;
  const control::RunResult result = play.run(nobody);
  EXPECT_GT(result.ticks, 600u);  // the whole 12 s show at 50 Hz, and the soft stop
  EXPECT_EQ(play.controller.latched_fault().cause, control::FaultCause::none);
  std::vector<double> truth(rig.channels.size(), 0.0);
  std::unique_ptr<bool[]> known(new bool[rig.channels.size()]());
  figure.measure(truth, std::span<bool>(known.get(), rig.channels.size()));
  for (std::size_t c = 0; c < rig.channels.size(); ++c) EXPECT_TRUE(known[c]) << rig.channels[c].name;
  return truth;
}

TEST(MaestroUsbFigure, PlaysTheExampleShowOnTheSimulatedUsbMaestroAsOnTheSerialOne) {
  const rig::Rig usb_rig = config::load_rig_file(AVAR_SOURCE_DIR "/examples/rigs/maestro-usb.yaml");
  assembly::LinkSelection simulate;
  simulate.simulate_all = true;
  assembly::FigureLinks usb_figure(usb_rig, simulate);
  EXPECT_EQ(usb_figure.describe(0), "simulated Maestro (12 channels) on USB (serial 00012345)");
  EXPECT_TRUE(usb_figure.reports_telemetry(0));
  const std::vector<double> usb_end = usb_figure_play(usb_rig, usb_figure);

  // Every tick was 8 Set Targets and one read of the servo records, and went to the device.
  usb_figure.with_simulated_usb(0, [](sim::UsbDeviceHost& host) {
    EXPECT_GT(host.transfers(), 600u * 9u);
    host.with_device([](sim::UsbControlDevice& d) {
      const auto& maestro = dynamic_cast<sim::SimMaestroUsb&>(d);
      EXPECT_EQ(maestro.stalls(), 0u);
      EXPECT_NE(maestro.target(0), 0);  // the jaw is still driven after the soft stop
    });
  });
  const firmware_iface::LinkCounters k = usb_figure.counters(0);
  EXPECT_GT(k.replies, 600u);
  EXPECT_EQ(k.timeouts, 0u);
  EXPECT_GT(usb_figure.bytes_sent(), 0u);
  EXPECT_THROW(usb_figure.with_simulated(0, [](sim::ByteDevice&) {}), std::invalid_argument);

  // The same figure on the serial Maestro, simulated behind a pseudo-terminal: the same servo
  // model under the same targets ends in the same pose.
  const rig::Rig serial_rig = config::load_rig_file(AVAR_SOURCE_DIR "/examples/rigs/hello-head.yaml");
  assembly::FigureLinks serial_figure(serial_rig, {});
  EXPECT_THROW(serial_figure.with_simulated_usb(0, [](sim::UsbDeviceHost&) {}), std::invalid_argument);
  const std::vector<double> serial_end = usb_figure_play(serial_rig, serial_figure);
  ASSERT_EQ(usb_end.size(), serial_end.size());
  for (std::size_t c = 0; c < usb_end.size(); ++c) EXPECT_NEAR(usb_end[c], serial_end[c], 1e-9) << usb_rig.channels[c].name;
}

TEST(MaestroUsbFigure, AnExplicitPortOpensTheVirtualSerialPortInstead) {
  const rig::Rig rig = config::load_rig_file(AVAR_SOURCE_DIR "/examples/rigs/maestro-usb.yaml");
  EXPECT_FALSE(assembly::maestro_port_is_serial(rig.links[0], ""));             // found on USB
  EXPECT_TRUE(assembly::maestro_port_is_serial(rig.links[0], "/dev/ttyACM0"));  // --port /dev/ttyACM0
  // --port sim still simulates it on USB.
  assembly::LinkSelection sim_port;
  sim_port.port = "sim";
  assembly::FigureLinks figure(rig, sim_port);
  EXPECT_EQ(figure.describe(0), "simulated Maestro (12 channels) on USB (serial 00012345)");
}

TEST(MaestroUsbFigure, ARealLinkWithoutItsMaestroSaysWhatIsMissingAtTheUsbSetting) {
  const std::string path = AVAR_SOURCE_DIR "/examples/rigs/maestro-usb.yaml";
  const rig::Rig rig = config::load_rig_file(path);
  try {
    assembly::FigureLinks figure(rig, {});
    GTEST_SKIP() << "a Maestro with serial 00012345 is attached";
  } catch (const InputError& e) {
    const std::string message = e.what();
    const std::string at = path + ":12:35: link 'head': ";
    ASSERT_EQ(message.rfind(at, 0), 0u) << message;
    const std::string what = message.substr(at.size());
    EXPECT_TRUE(what.rfind("no Maestro with serial 00012345 on USB (found: ", 0) == 0 ||
                what.rfind("libusb: no USB on this machine (", 0) == 0)
        << what;
  }
}

}  // namespace
}  // namespace avar
