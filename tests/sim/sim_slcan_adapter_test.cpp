// The simulated Lawicel adapter byte for byte: the checklist of slcan.md §4 (state rules,
// validation, replies), frames to and from its bus, timestamps and the Linux error lines.
#include "avar/sim/sim_slcan_adapter.hpp"

#include <gtest/gtest.h>

#include <string>

#include "../support/can_responder_node.hpp"

namespace avar::sim {
namespace {

using firmware_iface::can_data_frame;
using test::CanResponderNode;

/// Sends `text` to the adapter and returns everything it answered ("\a" for BEL).
std::string adapter_says(SimSlcanAdapter& adapter, const std::string& text) {
  adapter.receive(std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
  std::string out;
  std::array<std::uint8_t, 64> chunk{};
  for (std::size_t n = adapter.take_replies(chunk); n > 0; n = adapter.take_replies(chunk))
    out.append(reinterpret_cast<const char*>(chunk.data()), n);
  return out;
}

TEST(SimSlcanAdapter, AnswersTheOpenSequenceAsTheNoteSays) {
  SimSlcanAdapter adapter;
  EXPECT_EQ(adapter_says(adapter, "C\r"), "\a");  // already closed: Lawicel refuses
  EXPECT_EQ(adapter_says(adapter, "S7\r"), "\r");
  EXPECT_EQ(adapter.bitrate_code(), 7);
  EXPECT_EQ(adapter_says(adapter, "S9\r"), "\a");  // python-can's S9 is no code here
  EXPECT_EQ(adapter_says(adapter, "S8\r"), "\r");
  EXPECT_EQ(adapter_says(adapter, "V\r"), "V1013\r");
  EXPECT_EQ(adapter_says(adapter, "N\r"), "NA123\r");
  EXPECT_EQ(adapter_says(adapter, "O\r"), "\r");
  EXPECT_TRUE(adapter.is_open());
  EXPECT_EQ(adapter_says(adapter, "O\r"), "\a");   // already open
  EXPECT_EQ(adapter_says(adapter, "S6\r"), "\a");  // no bitrate change while open
  EXPECT_EQ(adapter_says(adapter, "s031C\r"), "\a");
  EXPECT_EQ(adapter_says(adapter, "C\r"), "\r");
  EXPECT_FALSE(adapter.is_open());
  EXPECT_EQ(adapter_says(adapter, "s031C\r"), "\r");  // custom timing while closed
  EXPECT_EQ(adapter.bitrate_code(), -1);
  EXPECT_EQ(adapter_says(adapter, "\r"), "\r");
  EXPECT_EQ(adapter_says(adapter, "?\r"), "\a");
  EXPECT_EQ(adapter_says(adapter, "Z1\r"), "\r");  // L8
  EXPECT_TRUE(adapter.timestamps());
  EXPECT_EQ(adapter_says(adapter, "Z2\r"), "\a");
  EXPECT_EQ(adapter_says(adapter, "F\r"), "\a");  // flags only while open
}

TEST(SimSlcanAdapter, RefusesFramesWhileClosedAndInvalidOnes) {
  CanResponderNode node{0x123};
  SimSlcanAdapter adapter({}, {&node});
  EXPECT_EQ(adapter_says(adapter, "t1230\r"), "\a");  // closed
  ASSERT_EQ(adapter_says(adapter, "O\r"), "\r");
  // Id out of range, DLC 9, a pair short, extended id out of range, timestamp digits, not hex.
  for (const char* bad : {"t8000\r", "t1239\r", "t123211\r", "T200000000\r", "t12300000\r", "tXYZ0\r"})
    EXPECT_EQ(adapter_says(adapter, bad), "\a") << bad;
  EXPECT_EQ(adapter_says(adapter, std::string(70, 't') + "\r"), "\a");  // longer than any command
  EXPECT_TRUE(node.heard.empty());
  EXPECT_EQ(adapter.transmitted(), 0u);
}

TEST(SimSlcanAdapter, FramesReachTheBusAndRepliesComeBackAsLines) {
  CanResponderNode node{0x345};
  SimSlcanAdapter adapter({}, {&node});
  ASSERT_EQ(adapter_says(adapter, "O\r"), "\r");
  // L5: a CANable answers a bare CR (acks off), then the node's reply arrives as a line.
  EXPECT_EQ(adapter_says(adapter, "t34580123456789ABCDEF\r"), "\rt34680123456789ABCDEF\r");
  ASSERT_EQ(node.heard.size(), 1u);
  EXPECT_EQ(node.heard[0].id, 0x345u);
  EXPECT_EQ(adapter_says(adapter, "r3452\r"), "\rt34620001\r");       // RTR answered with 00 01
  EXPECT_EQ(adapter_says(adapter, "t02c80000803f00000000\r"), "\r");  // L9 in lower case: accepted
  EXPECT_EQ(node.heard.back().id, 0x02Cu);
  EXPECT_EQ(adapter.transmitted(), 3u);
}

TEST(SimSlcanAdapter, LawicelAcksWhenConfigured) {
  SimSlcanConfig config;
  config.transmit_acks = true;
  SimSlcanAdapter adapter(config);
  ASSERT_EQ(adapter_says(adapter, "O\r"), "\r");
  EXPECT_EQ(adapter_says(adapter, "t34580123456789ABCDEF\r"), "z\r");       // L5
  EXPECT_EQ(adapter_says(adapter, "T1234567880123456789ABCDEF\r"), "Z\r");  // L6
  EXPECT_EQ(adapter_says(adapter, "t00231199FF\r"), "z\r");                 // L7
}

TEST(SimSlcanAdapter, ListenOnlyReceivesButNeverTransmits) {
  CanResponderNode node{0x123};
  SimSlcanAdapter adapter({}, {&node});
  ASSERT_EQ(adapter_says(adapter, "L\r"), "\r");
  EXPECT_TRUE(adapter.listen_only());
  EXPECT_EQ(adapter_says(adapter, "t1230\r"), "\a");
  EXPECT_TRUE(node.heard.empty());
  node.queue(can_data_frame(0x042, std::vector<std::uint8_t>{0xBE, 0xEF}));
  adapter.advance(0.001);
  EXPECT_EQ(adapter_says(adapter, ""), "t0422BEEF\r");
}

TEST(SimSlcanAdapter, TimestampsFollowTheBusClockInRollingMilliseconds) {
  CanResponderNode node{0x123};
  SimSlcanAdapter adapter({}, {&node});
  ASSERT_EQ(adapter_says(adapter, "Z1\rO\r"), "\r\r");
  adapter.advance(61.25);  // past one minute: the timestamp wraps
  node.queue(can_data_frame(0x010, std::vector<std::uint8_t>{}));
  adapter.advance(0.5);  // the frame goes out at once, at 61.25 s
  EXPECT_EQ(adapter_says(adapter, ""),
            "t0100"
            "04E2\r");  // 61.25 s -> 1250 ms = 0x04E2
}

TEST(SimSlcanAdapter, BusErrorsBecomeLinuxLinesAndStatusFlags) {
  SimSlcanAdapter adapter;
  ASSERT_EQ(adapter_says(adapter, "O\r"), "\r");
  adapter.bus().inject_error(firmware_iface::kCanErrorWarning | firmware_iface::kCanErrorAck);
  adapter.flush_bus();
  EXPECT_EQ(adapter_says(adapter, ""), "sw000096\re1a\r");
  EXPECT_EQ(adapter_says(adapter, "F\r"), "F04\r");  // Lawicel bit 2: error warning
  EXPECT_EQ(adapter_says(adapter, "F\r"), "F00\r");  // cleared by reading
  adapter.bus().inject_bus_off();
  adapter.flush_bus();
  EXPECT_EQ(adapter_says(adapter, ""), "sb000256\r");
  EXPECT_EQ(adapter_says(adapter, "t1230\r"), "\a");   // bus-off: nothing goes out
  EXPECT_EQ(adapter_says(adapter, "F\r"), "FA0\r");    // bus error + error passive
  ASSERT_EQ(adapter_says(adapter, "C\rO\r"), "\r\r");  // closing and opening restarts it
  EXPECT_EQ(adapter_says(adapter, "t1230\r"), "\r");
}

TEST(SimSlcanAdapter, AWrongBitrateHearsNothingAndMeetsErrors) {
  CanResponderNode node{0x123};
  SimSlcanAdapter adapter({}, {&node});  // the bus runs at 1 Mbit/s
  ASSERT_EQ(adapter_says(adapter, "S6\rO\r"), "\r\r");
  EXPECT_EQ(adapter_says(adapter, "t1230\r"), "\re1s\r");
  EXPECT_TRUE(node.heard.empty());
  node.queue(can_data_frame(0x042, std::vector<std::uint8_t>{}));
  adapter.advance(0.001);
  EXPECT_EQ(adapter_says(adapter, ""), "");
}

TEST(SimSlcanAdapter, AClosedAdapterReportsNothing) {
  CanResponderNode node{0x123};
  SimSlcanAdapter adapter({}, {&node});
  node.queue(can_data_frame(0x042, std::vector<std::uint8_t>{}));
  adapter.bus().inject_error(firmware_iface::kCanErrorPassive);
  adapter.advance(0.001);
  EXPECT_EQ(adapter_says(adapter, ""), "");  // never unsolicited text while closed
  EXPECT_EQ(adapter.bytes_received(), 0u);
}

}  // namespace
}  // namespace avar::sim
