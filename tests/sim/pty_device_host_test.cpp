// The pseudo-terminal host, driven the way a serial driver drives /dev/ttyACM0: plain POSIX
// open(), write() and read() on the slave side.
#include "avar/sim/pty_device_host.hpp"

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <limits>
#include <thread>
#include <vector>

#include "avar/sim/sim_maestro.hpp"

namespace avar::sim {
namespace {

using namespace std::chrono_literals;
using Bytes = std::vector<std::uint8_t>;

/// Opens the slave as a serial driver does; raw unless asked to keep the settings it finds.
int open_slave(const std::string& path, bool make_raw = true) {
  const int fd = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (fd >= 0 && make_raw) {
    termios t{};
    ::tcgetattr(fd, &t);
    ::cfmakeraw(&t);
    ::tcsetattr(fd, TCSANOW, &t);
  }
  return fd;
}

bool write_all(int fd, const Bytes& bytes) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

/// Reads exactly n bytes, waiting at most 2 s for each burst (a missing reply fails the test
/// instead of hanging it).
Bytes read_exact(int fd, std::size_t n) {
  Bytes out(n);
  std::size_t got = 0;
  while (got < n) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 2000) <= 0) break;
    const ssize_t r = ::read(fd, out.data() + got, n - got);
    if (r <= 0) break;
    got += static_cast<std::size_t>(r);
  }
  out.resize(got);
  return out;
}

TEST(PtyDeviceHost, AnswersAQueryThroughTheSlaveSide) {
  SimMaestro device(SimMaestroConfig{});
  PtyDeviceHost host(device, PtyDeviceHost::Clock::stepped);
  EXPECT_EQ(host.slave_path().rfind("/dev/pts/", 0), 0u) << host.slave_path();
  const int fd = open_slave(host.slave_path());
  ASSERT_GE(fd, 0);
  ASSERT_TRUE(write_all(fd, {0x84, 0x00, 0x70, 0x2E, 0x90, 0x00}));  // M1, then Get Position
  EXPECT_EQ(read_exact(fd, 2), (Bytes{0x70, 0x17}));                 // M12
  EXPECT_TRUE(host.wait_consumed(6, 2s));
  EXPECT_EQ(host.with_device([&](ByteDevice&) { return device.target(0); }), 6000);
  ::close(fd);
}

TEST(PtyDeviceHost, ThePtyIsRawWhateverTheClientLeavesUnset) {
  // Bytes a cooked terminal would alter: LF written by the client (ONLCR: LF -> CR LF), and in
  // the replies CR (ICRNL: CR -> LF) and 0x03 (ISIG: ^C is swallowed); canonical mode would hold
  // replies back until a newline, and echo would send them back to the device.
  SimMaestro device(SimMaestroConfig{});
  PtyDeviceHost host(device, PtyDeviceHost::Clock::stepped);
  const int fd = open_slave(host.slave_path(), /*make_raw=*/false);
  ASSERT_GE(fd, 0);
  const Bytes request{0x84, 0x03, 0x0A, 0x2E,               // ch 3 = 5898 (LF in the data)
                      0x84, 0x04, 0x0D, 0x2E,               // ch 4 = 5901
                      0x84, 0x05, 0x03, 0x2E,               // ch 5 = 5891
                      0x90, 0x03, 0x90, 0x04, 0x90, 0x05};  // Get Position ch 3, 4, 5
  ASSERT_TRUE(write_all(fd, request));
  EXPECT_EQ(read_exact(fd, 6), (Bytes{0x0A, 0x17, 0x0D, 0x17, 0x03, 0x17}));
  ASSERT_TRUE(host.wait_consumed(request.size(), 2s));
  host.with_device([&](ByteDevice& d) {
    EXPECT_EQ(d.bytes_received(), request.size());  // nothing echoed back
    EXPECT_EQ(device.target(3), 5898);
    EXPECT_EQ(device.target(4), 5901);
    EXPECT_EQ(device.target(5), 5891);
    EXPECT_EQ(device.errors(), 0);
  });
  ::close(fd);
}

TEST(PtyDeviceHost, WaitConsumedIsTheSyncPointOfSteppedTime) {
  SimMaestro device(SimMaestroConfig{});
  PtyDeviceHost host(device, PtyDeviceHost::Clock::stepped);
  EXPECT_TRUE(host.wait_consumed(0, 0ms));
  EXPECT_FALSE(host.wait_consumed(1, 20ms));  // nothing written: times out
  const int fd = open_slave(host.slave_path());
  ASSERT_GE(fd, 0);
  std::atomic<bool> woke{false};
  std::thread waiter([&] { woke = host.wait_consumed(4, 5s); });
  ASSERT_TRUE(write_all(fd, {0x84, 0x00}));
  ASSERT_TRUE(write_all(fd, {0x70, 0x2E}));
  waiter.join();
  EXPECT_TRUE(woke);
  // Once consumed, the command has taken effect and simulated time can be stepped.
  host.with_device([&](ByteDevice& d) {
    EXPECT_EQ(d.bytes_received(), 4u);
    EXPECT_EQ(device.target(0), 6000);
    d.advance(0.02);
  });
  EXPECT_FALSE(host.wait_consumed(5, 20ms));
  ::close(fd);
}

TEST(PtyDeviceHost, WaitUntilSeesEveryChange) {
  SimMaestro device(SimMaestroConfig{});
  PtyDeviceHost host(device, PtyDeviceHost::Clock::stepped);
  const int fd = open_slave(host.slave_path());
  ASSERT_GE(fd, 0);
  std::atomic<bool> at_target{false};
  std::thread waiter([&] { at_target = host.wait_until([&](ByteDevice&) { return device.target(1) == 8000; }, 5s); });
  ASSERT_TRUE(write_all(fd, {0x84, 0x01, 0x40, 0x3E}));
  waiter.join();
  EXPECT_TRUE(at_target);
  std::atomic<bool> moved{false};
  std::thread watcher([&] { moved = host.wait_until([&](ByteDevice&) { return device.servo_position_us(1) > 1600; }, 5s); });
  host.with_device([](ByteDevice& d) { d.advance(0.5); });  // wakes the watcher
  watcher.join();
  EXPECT_TRUE(moved);
  ::close(fd);
}

TEST(PtyDeviceHost, ClientsMayOpenAndCloseTheSlaveRepeatedlyWithoutTheHostSpinning) {
  SimMaestro device(SimMaestroConfig{});
  PtyDeviceHost host(device, PtyDeviceHost::Clock::stepped);
  constexpr int kRounds = 20;
  for (int i = 0; i < kRounds; ++i) {
    const int fd = open_slave(host.slave_path());
    ASSERT_GE(fd, 0);
    ASSERT_TRUE(write_all(fd, {0xA1}));
    ASSERT_EQ(read_exact(fd, 2), (Bytes{0x00, 0x00})) << "round " << i;
    ::close(fd);
  }
  EXPECT_TRUE(host.wait_consumed(kRounds, 2s));
  // One wake-up per burst of bytes; with no client open and nothing written the host sleeps in
  // poll() (a master that reported a hang-up would wake it over and over).
  const std::uint64_t woken = host.serve_wakeups();
  EXPECT_GE(woken, static_cast<std::uint64_t>(kRounds));
  EXPECT_LE(woken, static_cast<std::uint64_t>(2 * kRounds));
  EXPECT_FALSE(host.wait_consumed(kRounds + 1, 50ms));
  EXPECT_EQ(host.serve_wakeups(), woken);
  // And the next client is served as the first was.
  const int fd = open_slave(host.slave_path());
  ASSERT_TRUE(write_all(fd, {0xA1}));
  EXPECT_EQ(read_exact(fd, 2), (Bytes{0x00, 0x00}));
  ::close(fd);
}

TEST(PtyDeviceHost, LongBurstsGetEveryReply) {
  SimMaestro device(SimMaestroConfig{});
  PtyDeviceHost host(device, PtyDeviceHost::Clock::stepped);
  const int fd = open_slave(host.slave_path());
  ASSERT_GE(fd, 0);
  const Bytes queries(3000, 0xA1);  // 1-byte Get Errors, 2-byte replies: more out than in
  ASSERT_TRUE(write_all(fd, queries));
  const Bytes answers = read_exact(fd, 6000);
  EXPECT_EQ(answers, Bytes(6000, 0x00));
  EXPECT_TRUE(host.wait_consumed(3000, 2s));
  ::close(fd);
}

TEST(PtyDeviceHost, OwnerStepsTimeWhileClientsTalk) {
  SimMaestro device(SimMaestroConfig{});
  PtyDeviceHost host(device, PtyDeviceHost::Clock::stepped);
  const int fd = open_slave(host.slave_path());
  ASSERT_GE(fd, 0);
  ASSERT_TRUE(write_all(fd, {0x84, 0x00, 0x20, 0x1F, 0x87, 0x00, 0x04, 0x00, 0x84, 0x00, 0x40, 0x3E}));
  ASSERT_TRUE(host.wait_consumed(12, 2s));
  std::atomic<bool> done{false};
  std::thread stepper([&] {
    for (int i = 0; i < 200; ++i) host.with_device([](ByteDevice& d) { d.advance(0.01); });
    done = true;
  });
  for (int i = 0; i < 50; ++i) {
    ASSERT_TRUE(write_all(fd, {0x90, 0x00}));
    const Bytes reply = read_exact(fd, 2);
    ASSERT_EQ(reply.size(), 2u);
    const int q = reply[0] | (reply[1] << 8);
    ASSERT_GE(q, 4000);
    ASSERT_LE(q, 8000);
  }
  stepper.join();
  EXPECT_TRUE(done);
  // 2 s at 100 µs/s: 200 µs of the way.
  EXPECT_NEAR(host.with_device([&](ByteDevice&) { return device.output_pulse(0); }), 4000 + 800, 1e-6);
  ::close(fd);
}

TEST(PtyDeviceHost, WallClockModeMovesTheServosByItself) {
  SimMaestroConfig config;
  config.channels[0].initial_position_us = 1000;
  SimMaestro device(config);
  PtyDeviceHost host(device, PtyDeviceHost::Clock::wall);
  const int fd = open_slave(host.slave_path());
  ASSERT_GE(fd, 0);
  ASSERT_TRUE(write_all(fd, {0x84, 0x00, 0x40, 0x3E}));  // 2000 µs
  // The host thread advances the device on its own; wait on the device's state.
  EXPECT_TRUE(host.wait_until([&](ByteDevice&) { return device.servo_position_us(0) > 1900; }, 10s));
  ::close(fd);
}

TEST(PtyDeviceHost, ShutsDownCleanlyWhileAClientHoldsTheSlave) {
  SimMaestro device(SimMaestroConfig{});
  int fd = -1;
  {
    PtyDeviceHost host(device, PtyDeviceHost::Clock::wall);
    fd = open_slave(host.slave_path());
    ASSERT_GE(fd, 0);
    ASSERT_TRUE(write_all(fd, {0xA1}));
    EXPECT_EQ(read_exact(fd, 2), (Bytes{0x00, 0x00}));
  }
  // The master is gone: the client sees a hang-up, not a blocked read.
  pollfd p{fd, POLLIN, 0};
  ASSERT_EQ(::poll(&p, 1, 2000), 1);
  EXPECT_TRUE(p.revents & (POLLHUP | POLLERR | POLLIN));
  std::array<std::uint8_t, 1> byte{};
  EXPECT_LE(::read(fd, byte.data(), 1), 0);
  ::close(fd);
}

}  // namespace
}  // namespace avar::sim
