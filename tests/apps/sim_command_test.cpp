// `avar sim maestro --pty` as another program uses it: read the port path from its output, talk
// to it, stop it with Ctrl-C.
#include <gtest/gtest.h>

#include <array>

#include "../support/child_process.hpp"
#include "avar/firmware_iface/serial_transport.hpp"

namespace avar::app {
namespace {

TEST(SimCommand, ServesAMaestroOnAPseudoTerminalUntilInterrupted) {
  testing::ChildProcess sim({AVAR_BINARY, "sim", "maestro", "--pty", "--channels", "12"});
  ASSERT_TRUE(sim.started());
  std::string path = sim.read_out_until("\n");
  ASSERT_FALSE(path.empty());
  path.pop_back();
  EXPECT_EQ(path.rfind("/dev/pts/", 0), 0u) << path;
  {
    firmware_iface::SerialTransport port(path, 115200);
    const std::array<std::uint8_t, 6> set_then_get{0x84, 0x01, 0x70, 0x2E, 0x90, 0x01};
    ASSERT_EQ(port.write(set_then_get), Status::ok);
    std::array<std::uint8_t, 2> reply{};
    ASSERT_EQ(port.read_exact(reply, std::chrono::milliseconds(2000)), Status::ok);
    EXPECT_EQ(reply, (std::array<std::uint8_t, 2>{0x70, 0x17}));
  }
  sim.signal(SIGINT);
  EXPECT_EQ(sim.wait(), 0) << sim.err();
  EXPECT_NE(sim.err().find("simulated Maestro (12 channels"), std::string::npos) << sim.err();
  EXPECT_NE(sim.err().find("stopped after 6 bytes"), std::string::npos) << sim.err();
}

TEST(SimCommand, RefusesWithoutATransport) {
  testing::ChildProcess sim({AVAR_BINARY, "sim", "maestro"});
  EXPECT_EQ(sim.wait(), 2);
  EXPECT_NE(sim.err().find("--pty"), std::string::npos) << sim.err();
}

}  // namespace
}  // namespace avar::app
