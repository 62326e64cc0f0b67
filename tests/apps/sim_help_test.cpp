// `avar sim NAME --help` teaches, for every protocol of the registry and every CAN drive protocol:
// the test walks the registry, so a new protocol without a simulator offer fails here. Also: a
// serial device is served on a pseudo-terminal without being told, and a device that lives only
// inside the avar that drives it says how to reach it.
#include <gtest/gtest.h>

#include <string>

#include "../support/child_process.hpp"
#include "avar/assembly/can_drive.hpp"
#include "avar/assembly/protocol.hpp"
#include "avar/firmware_iface/serial_transport.hpp"

namespace avar::app {
namespace {

/// Runs `avar sim NAME --help` and checks it exits 0 with help that names NAME and says more
/// than its options.
void expect_teaching_help(const std::string& name) {
  testing::ChildProcess help({AVAR_BINARY, "sim", name, "--help"});
  ASSERT_EQ(help.wait_for(std::chrono::seconds(60)), 0) << name << ": " << help.err();
  const std::string& text = help.out();
  EXPECT_NE(text.find("sim " + name), std::string::npos) << text;
  EXPECT_NE(text.find("Served on:"), std::string::npos) << text;
  EXPECT_NE(text.find("Example:"), std::string::npos) << text;
  EXPECT_GT(text.size(), 400u) << text;
}

TEST(SimHelp, EveryProtocolOfTheRegistryHasATeachingHelp) {
  for (const assembly::Protocol* p : assembly::protocols()) {
    SCOPED_TRACE(p->name);
    EXPECT_STREQ(p->sim.name, p->name);
    expect_teaching_help(p->name);
  }
}

TEST(SimHelp, EveryCanDriveProtocolHasATeachingHelp) {
  for (const assembly::CanDriveProtocol* d : assembly::can_drive_protocols()) {
    SCOPED_TRACE(d->name);
    EXPECT_STREQ(d->sim.name, d->name);
    expect_teaching_help(d->name);
  }
}

TEST(SimHelp, SimItselfListsEveryDeviceAndAnExample) {
  testing::ChildProcess help({AVAR_BINARY, "sim", "--help"});
  ASSERT_EQ(help.wait_for(std::chrono::seconds(60)), 0) << help.err();
  for (const assembly::Protocol* p : assembly::protocols())
    EXPECT_NE(help.out().find(std::string("  ") + p->name), std::string::npos) << p->name << "\n" << help.out();
  EXPECT_NE(help.out().find("pseudo-terminal"), std::string::npos) << help.out();
  EXPECT_NE(help.out().find("Example:"), std::string::npos) << help.out();
}

TEST(SimHelp, AnOdriveAloneIsServedBehindAnSlcanAdapterOnAPseudoTerminal) {
  testing::ChildProcess sim({AVAR_BINARY, "sim", "odrive", "--ids", "2"});
  ASSERT_TRUE(sim.started());
  std::string path = sim.read_out_until("\n");
  ASSERT_FALSE(path.empty()) << sim.err();
  path.pop_back();
  EXPECT_EQ(path.rfind("/dev/pts/", 0), 0u) << path;
  sim.signal(SIGINT);
  EXPECT_EQ(sim.wait(), 0) << sim.err();
  EXPECT_NE(sim.err().find("simulated SLCAN adapter with ODrive at node 2"), std::string::npos) << sim.err();
}

TEST(SimHelp, AnSacnReceiverIsServedOnLoopback) {
  testing::ChildProcess sim({AVAR_BINARY, "sim", "sacn", "--universe", "7"});
  ASSERT_TRUE(sim.started());
  const std::string endpoint = sim.read_out_until("\n");
  EXPECT_EQ(endpoint.rfind("127.0.0.1:", 0), 0u) << endpoint << sim.err();
  sim.signal(SIGTERM);
  EXPECT_EQ(sim.wait(), 0) << sim.err();
  EXPECT_NE(sim.err().find("simulated sACN receiver (universe 7)"), std::string::npos) << sim.err();
}

TEST(SimHelp, AGpioChipSaysItLivesInsideTheAvarThatDrivesIt) {
  testing::ChildProcess sim({AVAR_BINARY, "sim", "gpio"});
  EXPECT_EQ(sim.wait(), 2);
  EXPECT_NE(sim.err().find("--sim"), std::string::npos) << sim.err();
}

}  // namespace
}  // namespace avar::app
