// `avar sim maestro --pty` as another program uses it: read the port path from its output, talk
// to it, stop it with Ctrl-C.
#include <gtest/gtest.h>

#include <array>

#include "../support/child_process.hpp"
#include "avar/firmware_iface/dynamixel_codec.hpp"
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

TEST(SimCommand, ServesADynamixelBusThatAnswersPings) {
  testing::ChildProcess sim({AVAR_BINARY, "sim", "dynamixel", "--pty", "--ids", "3,7"});
  ASSERT_TRUE(sim.started());
  std::string path = sim.read_out_until("\n");
  ASSERT_FALSE(path.empty());
  path.pop_back();
  {
    firmware_iface::SerialTransport port(path, 1000000);
    // Ping ID 7, then read its model number's reply: FF FF FD 00 07 07 00 55 00 FC 03 2D CRC CRC.
    std::array<std::uint8_t, 16> ping{};
    const std::size_t n = firmware_iface::dynamixel::encode_ping(ping, 7);
    ASSERT_EQ(port.write(std::span(ping.data(), n)), Status::ok);
    std::array<std::uint8_t, 14> reply{};
    ASSERT_EQ(port.read_exact(reply, std::chrono::milliseconds(2000)), Status::ok);
    EXPECT_EQ(reply[4], 7);
    EXPECT_EQ(reply[7], 0x55);
    EXPECT_EQ(firmware_iface::dynamixel::read_u16(std::span(reply).subspan(9, 2)), 1020);  // XM430-W350
  }
  sim.signal(SIGTERM);
  EXPECT_EQ(sim.wait(), 0) << sim.err();
  EXPECT_NE(sim.err().find("simulated Dynamixel bus (IDs 3,7)"), std::string::npos) << sim.err();
}

TEST(SimCommand, RejectsDuplicateDynamixelIds) {
  testing::ChildProcess sim({AVAR_BINARY, "sim", "dynamixel", "--pty", "--ids", "3,3"});
  EXPECT_EQ(sim.wait(), 2);
  EXPECT_NE(sim.err().find("--ids: 3 is given twice"), std::string::npos) << sim.err();
}

TEST(SimCommand, RefusesWithoutATransport) {
  testing::ChildProcess sim({AVAR_BINARY, "sim", "maestro"});
  EXPECT_EQ(sim.wait(), 2);
  EXPECT_NE(sim.err().find("--pty"), std::string::npos) << sim.err();
}

}  // namespace
}  // namespace avar::app
