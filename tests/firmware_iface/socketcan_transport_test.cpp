// SocketCanTransport: the frame and error-frame conversions everywhere; loopback, filters and
// deadlines on vcan0 where the kernel has it (the tests skip, saying what is missing, elsewhere).
#include "avar/firmware_iface/socketcan_transport.hpp"

#include <linux/can.h>
#include <linux/can/error.h>
#include <net/if.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "avar/core/input_error.hpp"

namespace avar::firmware_iface {
namespace {

using namespace std::chrono_literals;

constexpr const char* kSocketCanTestInterface = "vcan0";

/// Why SocketCAN tests cannot run here, or "" when vcan0 is up.
std::string socketcan_missing() {
  const int fd = ::socket(PF_CAN, SOCK_RAW, CAN_RAW);
  if (fd < 0)
    return "this kernel has no SocketCAN (socket(AF_CAN) failed); on a machine with it: sudo modprobe vcan && "
           "sudo ip link add dev vcan0 type vcan && sudo ip link set up vcan0";
  ::close(fd);
  if (::if_nametoindex(kSocketCanTestInterface) == 0)
    return "no vcan0 interface: sudo modprobe vcan && sudo ip link add dev vcan0 type vcan && sudo ip link set up vcan0";
  return "";
}

#define SOCKETCAN_REQUIRE_VCAN0()                                                                   \
  do {                                                                                              \
    if (const std::string missing = socketcan_missing(); !missing.empty()) GTEST_SKIP() << missing; \
  } while (0)

TEST(SocketCanConversion, DataAndRemoteFramesBothWays) {
  const std::vector<CanFrame> frames{can_data_frame(0x123, std::vector<std::uint8_t>{1, 2, 3}),
                                     can_data_frame(0x12345678, std::vector<std::uint8_t>{0xAA}, true),
                                     can_remote_frame(0x7FF, 8), can_remote_frame(0x1FFFFFFF, 0, true)};
  for (const CanFrame& f : frames) {
    ::can_frame k{};
    ASSERT_TRUE(socketcan::to_kernel(f, &k));
    EXPECT_EQ(k.can_id & CAN_EFF_FLAG, f.extended ? CAN_EFF_FLAG : 0u);
    EXPECT_EQ(k.can_id & CAN_RTR_FLAG, f.rtr ? CAN_RTR_FLAG : 0u);
    EXPECT_EQ(k.len, f.dlc);
    EXPECT_EQ(socketcan::from_kernel(k), f);
  }
  ::can_frame k{};
  EXPECT_FALSE(socketcan::to_kernel(can_data_frame(0x800, std::vector<std::uint8_t>{}), &k));
  CanFrame error;
  error.error = true;
  EXPECT_FALSE(socketcan::to_kernel(error, &k));
}

TEST(SocketCanConversion, KernelErrorFramesMapToErrorClasses) {
  const auto classes_of = [](std::uint32_t id, std::uint8_t crtl = 0) {
    ::can_frame k{};
    k.can_id = CAN_ERR_FLAG | id;
    k.len = CAN_ERR_DLC;
    k.data[1] = crtl;
    k.data[6] = 12;  // TX error counter
    k.data[7] = 34;  // RX error counter
    const CanFrame f = socketcan::from_kernel(k);
    EXPECT_TRUE(f.error);
    EXPECT_EQ(f.data[6], 12);
    EXPECT_EQ(f.data[7], 34);
    return f.id;
  };
  EXPECT_EQ(classes_of(CAN_ERR_BUSOFF), kCanErrorBusOff);
  EXPECT_EQ(classes_of(CAN_ERR_RESTARTED), kCanErrorRestarted);
  EXPECT_EQ(classes_of(CAN_ERR_ACK), kCanErrorAck);
  EXPECT_EQ(classes_of(CAN_ERR_PROT), kCanErrorProtocol);
  EXPECT_EQ(classes_of(CAN_ERR_BUSERROR), kCanErrorProtocol);
  EXPECT_EQ(classes_of(CAN_ERR_CRTL, CAN_ERR_CRTL_RX_WARNING), kCanErrorWarning);
  EXPECT_EQ(classes_of(CAN_ERR_CRTL, CAN_ERR_CRTL_TX_PASSIVE), kCanErrorPassive);
  EXPECT_EQ(classes_of(CAN_ERR_CRTL, CAN_ERR_CRTL_RX_OVERFLOW), kCanErrorOverrun);
  EXPECT_EQ(classes_of(CAN_ERR_CRTL | CAN_ERR_BUSOFF | CAN_ERR_ACK, CAN_ERR_CRTL_TX_WARNING),
            kCanErrorWarning | kCanErrorBusOff | kCanErrorAck);
  EXPECT_EQ(classes_of(CAN_ERR_LOSTARB), 0u);  // lost arbitration is flow, not an error
}

TEST(SocketCanTransport, AMissingInterfaceIsNamedWithHowToCreateIt) {
  try {
    SocketCanTransport t("avarnope0", 1'000'000);
    FAIL() << "opened a missing interface";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("avarnope0"), std::string::npos) << message;
    EXPECT_NE(message.find("ip link show avarnope0"), std::string::npos) << message;
    EXPECT_NE(message.find("sudo modprobe vcan && sudo ip link add dev avarnope0 type vcan"), std::string::npos) << message;
  }
}

TEST(SocketCanTransport, LoopbackSendAndReceiveOnVcan) {
  SOCKETCAN_REQUIRE_VCAN0();
  SocketCanTransport sender(kSocketCanTestInterface, 1'000'000);
  SocketCanTransport receiver(kSocketCanTestInterface, 1'000'000);
  receiver.discard_input();
  const std::array<CanFrame, 3> frames{can_data_frame(0x123, std::vector<std::uint8_t>{1, 2, 3}), can_remote_frame(0x124, 4),
                                       can_data_frame(0x1ABCDEF0, std::vector<std::uint8_t>(8, 0x77), true)};
  const auto before = receiver.now();
  ASSERT_EQ(sender.send(frames), Status::ok);
  for (const CanFrame& expected : frames) {
    CanFrame got;
    ASSERT_EQ(receiver.receive(&got, receiver.now() + 500ms), Status::ok);
    EXPECT_EQ(got, expected);
    EXPECT_GE(got.timestamp, before - 1ms);
    EXPECT_LE(got.timestamp, receiver.now());
  }
  EXPECT_EQ(sender.counters().frames_sent, 3u);
  EXPECT_EQ(receiver.counters().frames_received, 3u);
  EXPECT_EQ(receiver.name(), kSocketCanTestInterface);
  EXPECT_EQ(receiver.bitrate(), 1'000'000);
}

TEST(SocketCanTransport, FiltersLetOnlyTheirIdsThroughOnVcan) {
  SOCKETCAN_REQUIRE_VCAN0();
  SocketCanConfig config;
  config.filters = {{0x120, 0x7F0, false}};  // 0x120..0x12F, standard only
  SocketCanTransport receiver(kSocketCanTestInterface, 1'000'000, config);
  SocketCanTransport sender(kSocketCanTestInterface, 1'000'000);
  const std::array<CanFrame, 4> frames{
      can_data_frame(0x200, std::vector<std::uint8_t>{1}), can_data_frame(0x125, std::vector<std::uint8_t>{2}),
      can_data_frame(0x125, std::vector<std::uint8_t>{3}, true), can_data_frame(0x12F, std::vector<std::uint8_t>{4})};
  ASSERT_EQ(sender.send(frames), Status::ok);
  CanFrame got;
  ASSERT_EQ(receiver.receive(&got, receiver.now() + 500ms), Status::ok);
  EXPECT_EQ(got, frames[1]);
  ASSERT_EQ(receiver.receive(&got, receiver.now() + 500ms), Status::ok);
  EXPECT_EQ(got, frames[3]);
  EXPECT_EQ(receiver.receive(&got, receiver.now() + 20ms), Status::timeout);
}

TEST(SocketCanTransport, ReceiveWaitsUntilTheDeadlineOnVcan) {
  SOCKETCAN_REQUIRE_VCAN0();
  SocketCanTransport t(kSocketCanTestInterface, 1'000'000);
  t.discard_input();
  const auto deadline = t.now() + 30ms;
  CanFrame got;
  EXPECT_EQ(t.receive(&got, deadline), Status::timeout);
  EXPECT_GE(t.now(), deadline);
  EXPECT_EQ(t.receive(&got, t.now()), Status::timeout);  // a deadline now: one look
  ASSERT_EQ(t.reopen(), Status::ok);
  EXPECT_EQ(t.receive(&got, t.now() + 1ms), Status::timeout);
}

}  // namespace
}  // namespace avar::firmware_iface
