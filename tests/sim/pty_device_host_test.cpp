#include "avar/sim/pty_device_host.hpp"

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <array>

#include "avar/sim/sim_maestro.hpp"

namespace avar::sim {
namespace {

int open_raw(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDWR | O_NOCTTY);
  termios t{};
  tcgetattr(fd, &t);
  cfmakeraw(&t);
  tcsetattr(fd, TCSANOW, &t);
  return fd;
}

bool read_exact(int fd, std::uint8_t* out, std::size_t n) {
  std::size_t got = 0;
  while (got < n) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 2000) <= 0) return false;
    const ssize_t r = ::read(fd, out + got, n - got);
    if (r <= 0) return false;
    got += static_cast<std::size_t>(r);
  }
  return true;
}

TEST(PtyDeviceHost, AnswersAQueryThroughTheSlaveSide) {
  SimMaestro device(SimMaestroConfig{});
  PtyDeviceHost host(device, PtyDeviceHost::Clock::stepped);
  const int fd = open_raw(host.slave_path());
  ASSERT_GE(fd, 0);
  const std::array<std::uint8_t, 6> cmd{0x84, 0x00, 0x70, 0x2E, 0x90, 0x00};
  ASSERT_EQ(::write(fd, cmd.data(), cmd.size()), 6);
  std::array<std::uint8_t, 2> reply{};
  ASSERT_TRUE(read_exact(fd, reply.data(), 2));
  EXPECT_EQ(reply, (std::array<std::uint8_t, 2>{0x70, 0x17}));
  EXPECT_TRUE(host.wait_consumed(6, std::chrono::seconds(2)));
  EXPECT_FALSE(host.wait_consumed(7, std::chrono::milliseconds(20)));
  EXPECT_EQ(host.with_device([&](ByteDevice&) { return device.target(0); }), 6000);
  ::close(fd);
}

TEST(PtyDeviceHost, ClientsMayOpenAndCloseTheSlaveRepeatedly) {
  SimMaestro device(SimMaestroConfig{});
  PtyDeviceHost host(device, PtyDeviceHost::Clock::stepped);
  for (int i = 0; i < 20; ++i) {
    const int fd = open_raw(host.slave_path());
    ASSERT_GE(fd, 0);
    const std::array<std::uint8_t, 1> query{0xA1};
    ASSERT_EQ(::write(fd, query.data(), 1), 1);
    std::array<std::uint8_t, 2> reply{};
    ASSERT_TRUE(read_exact(fd, reply.data(), 2)) << "round " << i;
    ::close(fd);
  }
  EXPECT_TRUE(host.wait_consumed(20, std::chrono::seconds(2)));
}

TEST(PtyDeviceHost, WallClockModeMovesTheServosByItself) {
  SimMaestroConfig config;
  config.channels[0].initial_position_us = 1000;
  SimMaestro device(config);
  PtyDeviceHost host(device, PtyDeviceHost::Clock::wall);
  const int fd = open_raw(host.slave_path());
  const std::array<std::uint8_t, 4> cmd{0x84, 0x00, 0x40, 0x3E};  // 2000 µs
  ASSERT_EQ(::write(fd, cmd.data(), cmd.size()), 4);
  ASSERT_TRUE(host.wait_consumed(4, std::chrono::seconds(2)));
  // Wait on the device's state, not on time: the host thread advances it on its own.
  bool moved = false;
  for (int i = 0; i < 1000 && !moved; ++i) {
    pollfd none{-1, 0, 0};
    ::poll(&none, 0, 5);
    moved = host.with_device([&](ByteDevice&) { return device.servo_position_us(0) > 1900; });
  }
  EXPECT_TRUE(moved);
  ::close(fd);
}

}  // namespace
}  // namespace avar::sim
