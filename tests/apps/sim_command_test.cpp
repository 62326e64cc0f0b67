// `avar sim maestro|dynamixel|feetech|ssc32|dmx [--pty]` as another program uses it: read the port path from its output, talk
// to it, stop it with Ctrl-C.
#include <gtest/gtest.h>

#include <array>

#include "../support/child_process.hpp"
#include "avar/firmware_iface/dmx_codec.hpp"
#include "avar/firmware_iface/dynamixel_codec.hpp"
#include "avar/firmware_iface/feetech_codec.hpp"
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

TEST(SimCommand, ServesAFeetechBusThatAnswersReads) {
  testing::ChildProcess sim({AVAR_BINARY, "sim", "feetech", "--pty", "--ids", "4,6", "--series", "scs", "--baud", "500000"});
  ASSERT_TRUE(sim.started());
  std::string path = sim.read_out_until("\n");
  ASSERT_FALSE(path.empty());
  path.pop_back();
  {
    firmware_iface::SerialTransport port(path, 500000);
    std::array<std::uint8_t, 16> read{};
    const std::size_t n = firmware_iface::feetech::encode_read(read, 6, firmware_iface::feetech::kModelNumber, 2);
    ASSERT_EQ(port.write(std::span(read.data(), n)), Status::ok);
    std::array<std::uint8_t, 8> reply{};
    ASSERT_EQ(port.read_exact(reply, std::chrono::milliseconds(2000)), Status::ok);
    EXPECT_EQ(reply[2], 6);
    EXPECT_EQ(firmware_iface::feetech::get_word(firmware_iface::feetech::Series::scs, std::span(reply).subspan(5, 2)), 1284);
  }
  sim.signal(SIGINT);
  EXPECT_EQ(sim.wait(), 0) << sim.err();
  EXPECT_NE(sim.err().find("simulated Feetech SCS bus (IDs 4,6, 500000 baud)"), std::string::npos) << sim.err();
}

TEST(SimCommand, RejectsAFeetechBaudRateTheServosCannotDo) {
  testing::ChildProcess sim({AVAR_BINARY, "sim", "feetech", "--pty", "--baud", "123456"});
  EXPECT_EQ(sim.wait(), 2);
  EXPECT_NE(sim.err().find("--baud: a Feetech servo cannot run at 123456"), std::string::npos) << sim.err();
  testing::ChildProcess series({AVAR_BINARY, "sim", "feetech", "--pty", "--series", "xl"});
  EXPECT_EQ(series.wait(), 2);
  EXPECT_NE(series.err().find("--series: 'xl' is not a Feetech series"), std::string::npos) << series.err();
  testing::ChildProcess ids({AVAR_BINARY, "sim", "feetech", "--pty", "--ids", "1,254"});
  EXPECT_EQ(ids.wait(), 2);
  EXPECT_NE(ids.err().find("--ids: 254 is not a Feetech ID; expected 0 to 253"), std::string::npos) << ids.err();
}

TEST(SimCommand, ServesAnSsc32ThatAnswersPositionQueries) {
  testing::ChildProcess sim({AVAR_BINARY, "sim", "ssc32", "--pty"});
  ASSERT_TRUE(sim.started());
  std::string path = sim.read_out_until("\n");
  ASSERT_FALSE(path.empty());
  path.pop_back();
  {
    firmware_iface::SerialTransport port(path, 115200);
    const std::string line = "#5P1500\rQP5\r";
    ASSERT_EQ(port.write(std::span(reinterpret_cast<const std::uint8_t*>(line.data()), line.size())), Status::ok);
    std::array<std::uint8_t, 1> reply{};
    ASSERT_EQ(port.read_exact(reply, std::chrono::milliseconds(2000)), Status::ok);
    EXPECT_EQ(reply[0], 150);
  }
  sim.signal(SIGTERM);
  EXPECT_EQ(sim.wait(), 0) << sim.err();
  EXPECT_NE(sim.err().find("simulated SSC-32U"), std::string::npos) << sim.err();
}

TEST(SimCommand, ServesADmxWidgetThatAnswersItsParameters) {
  testing::ChildProcess sim({AVAR_BINARY, "sim", "dmx", "--pty"});
  ASSERT_TRUE(sim.started());
  std::string path = sim.read_out_until("\n");
  ASSERT_FALSE(path.empty());
  path.pop_back();
  {
    firmware_iface::SerialTransport port(path, 115200);
    std::array<std::uint8_t, 8> request{};
    const std::size_t n = firmware_iface::dmx::encode_get_widget_parameters(request);
    ASSERT_EQ(port.write(std::span(request.data(), n)), Status::ok);
    std::array<std::uint8_t, 10> reply{};
    ASSERT_EQ(port.read_exact(reply, std::chrono::milliseconds(2000)), Status::ok);
    EXPECT_EQ(reply[0], 0x7E);
    EXPECT_EQ(reply[1], 0x03);
    EXPECT_EQ(reply[9], 0xE7);
  }
  sim.signal(SIGINT);
  EXPECT_EQ(sim.wait(), 0) << sim.err();
  EXPECT_NE(sim.err().find("simulated DMX USB Pro"), std::string::npos) << sim.err();
}

TEST(SimCommand, ServesASerialDeviceOnAPseudoTerminalWithoutBeingTold) {
  testing::ChildProcess sim({AVAR_BINARY, "sim", "maestro"});
  ASSERT_TRUE(sim.started());
  std::string path = sim.read_out_until("\n");
  ASSERT_FALSE(path.empty()) << sim.err();
  path.pop_back();
  EXPECT_EQ(path.rfind("/dev/pts/", 0), 0u) << path;
  sim.signal(SIGINT);
  EXPECT_EQ(sim.wait(), 0) << sim.err();
  EXPECT_NE(sim.err().find("simulated Maestro (24 channels"), std::string::npos) << sim.err();
}

}  // namespace
}  // namespace avar::app
