// SerialTransport against the master side of a pseudo-terminal: the real libserial code path,
// with the test playing the device.
#include "avar/firmware_iface/serial_transport.hpp"

#include <fcntl.h>
#include <poll.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <array>
#include <gtest/gtest.h>
#include <string>
#include <vector>

#include "../support/temp_file.hpp"
#include "avar/core/input_error.hpp"

namespace avar::firmware_iface {
namespace {

struct Pty {
  int master = -1;
  int slave = -1;
  std::string path;
  Pty() {
    termios raw{};
    cfmakeraw(&raw);
    std::array<char, 128> name{};
    if (openpty(&master, &slave, name.data(), &raw, nullptr) != 0) throw std::runtime_error("openpty failed");
    path = name.data();
  }
  ~Pty() {
    ::close(slave);
    ::close(master);
  }
  std::vector<std::uint8_t> read_master(std::size_t n) const {
    std::vector<std::uint8_t> out;
    while (out.size() < n) {
      pollfd p{master, POLLIN, 0};
      if (::poll(&p, 1, 2000) <= 0) break;
      std::array<std::uint8_t, 256> buf{};
      const ssize_t got = ::read(master, buf.data(), std::min(buf.size(), n - out.size()));
      if (got <= 0) break;
      out.insert(out.end(), buf.begin(), buf.begin() + got);
    }
    return out;
  }
};

TEST(SerialTransport, WritesAndReadsRawBytesThroughAPseudoTerminal) {
  Pty pty;
  SerialTransport port(pty.path, 115200);
  const std::vector<std::uint8_t> sent{0x84, 0x00, 0x70, 0x2E, 0x0A, 0x0D, 0xFF, 0x11, 0x13};
  ASSERT_EQ(port.write(sent), Status::ok);
  EXPECT_EQ(port.bytes_written(), sent.size());
  EXPECT_EQ(pty.read_master(sent.size()), sent);  // no CR/LF translation, no XON/XOFF eaten

  const std::array<std::uint8_t, 3> reply{0x70, 0x0D, 0x11};
  ASSERT_EQ(::write(pty.master, reply.data(), reply.size()), 3);
  std::array<std::uint8_t, 3> got{};
  ASSERT_EQ(port.read_exact(got, std::chrono::milliseconds(1000)), Status::ok);
  EXPECT_EQ(got, reply);
}

TEST(SerialTransport, ReadTimesOutWhenTheDeviceStaysSilent) {
  Pty pty;
  SerialTransport port(pty.path, 115200);
  std::array<std::uint8_t, 2> got{};
  EXPECT_EQ(port.read_exact(got, std::chrono::milliseconds(20)), Status::timeout);
}

TEST(SerialTransport, DiscardDropsStaleInput) {
  Pty pty;
  SerialTransport port(pty.path, 115200);
  const std::array<std::uint8_t, 2> stale{0x01, 0x02};
  ASSERT_EQ(::write(pty.master, stale.data(), stale.size()), 2);
  ::tcdrain(pty.master);
  pollfd p{pty.slave, POLLIN, 0};
  ASSERT_GT(::poll(&p, 1, 1000), 0);
  port.discard_input();
  std::array<std::uint8_t, 1> got{};
  EXPECT_EQ(port.read_exact(got, std::chrono::milliseconds(20)), Status::timeout);
}

TEST(SerialTransport, SecondOpenOfTheSamePortIsRefusedAsBusy) {
  Pty pty;
  SerialTransport first(pty.path, 115200);
  try {
    SerialTransport second(pty.path, 115200);
    FAIL() << "second open succeeded";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, pty.path);
    EXPECT_NE(std::string(e.what()).find("busy"), std::string::npos) << e.what();
  }
}

TEST(SerialTransport, MissingPortNamesThePathAndWhatWasExpected) {
  try {
    SerialTransport port("/dev/ttyACM_avar_missing", 115200);
    FAIL() << "opened a missing port";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "/dev/ttyACM_avar_missing: cannot open serial port: No such file or directory; expected a serial "
                 "device such as /dev/ttyACM0 (is it plugged in?)");
  }
}

TEST(SerialTransport, RegularFileIsNotASerialDevice) {
  const std::string path = avar::testing::write_temp_file("not-a-port.txt", "x");
  EXPECT_THROW(SerialTransport(path, 115200), InputError);
}

TEST(SerialTransport, NonStandardBaudRateIsRejected) {
  Pty pty;
  try {
    SerialTransport port(pty.path, 12345);
    FAIL() << "accepted baud 12345";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("baud rate 12345"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(SerialTransport::is_supported_baud(115200));
  EXPECT_TRUE(SerialTransport::is_supported_baud(1000000));
  EXPECT_FALSE(SerialTransport::is_supported_baud(200000));
}

}  // namespace
}  // namespace avar::firmware_iface
