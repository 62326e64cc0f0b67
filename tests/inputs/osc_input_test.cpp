// OSC input: datagrams (golden bytes from the OSC 1.0 specification, and liblo's own encoding) to
// controls, then end to end over loopback UDP with liblo's lo_send as the sender.
#include "avar/inputs/osc_input.hpp"
#include "avar/core/monotonic_clock.hpp"

#include <arpa/inet.h>
#include <lo/lo.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "../support/osc_sender.hpp"
#include "../support/recording_control_sink.hpp"

#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

namespace avar::inputs {
namespace {

using avar::testing::eventually;
using avar::testing::OscSender;
using avar::testing::PostedControl;
using avar::testing::RecordingControlSink;

/// liblo's serialisation of a message (path, then what `fill` adds).
template <class Fill>
std::vector<std::uint8_t> osc_message_bytes(const char* path, Fill fill) {
  const lo_message m = lo_message_new();
  fill(m);
  std::size_t size = 0;
  void* data = lo_message_serialise(m, path, nullptr, &size);
  std::vector<std::uint8_t> bytes(static_cast<std::uint8_t*>(data), static_cast<std::uint8_t*>(data) + size);
  std::free(data);
  lo_message_free(m);
  return bytes;
}

std::vector<PostedControl> osc_posts_of(const std::vector<std::uint8_t>& packet, InputCounters* counters) {
  RecordingControlSink sink;
  *counters = dispatch_osc_packet(packet, sink, 42);
  return sink.posts();
}

TEST(OscPacket, GoldenBytesFromTheSpecification) {
  // OSC 1.0: the address, padded with NULs to 4 bytes; the type tag string ",f" padded; then a
  // big-endian float32. 0.5f = 0x3F000000.
  std::vector<std::uint8_t> packet;
  for (const char c : std::string("/avar/control/jaw")) packet.push_back(static_cast<std::uint8_t>(c));
  packet.insert(packet.end(), {0, 0, 0, ',', 'f', 0, 0, 0x3F, 0x00, 0x00, 0x00});
  ASSERT_EQ(packet.size(), 28u);
  EXPECT_EQ(osc_message_bytes("/avar/control/jaw", [](lo_message m) { lo_message_add_float(m, 0.5f); }), packet);
  InputCounters counters;
  const auto posts = osc_posts_of(packet, &counters);
  ASSERT_EQ(posts.size(), 1u);
  EXPECT_EQ(posts[0].name, "jaw");
  EXPECT_EQ(posts[0].value, 0.5);
  EXPECT_FALSE(posts[0].bipolar);
  EXPECT_EQ(posts[0].arrived_ns, 42);
  EXPECT_EQ(counters.messages, 1u);
  EXPECT_EQ(counters.ignored, 0u);

  // ",d" and a float64: -12.25 = 0xC028800000000000.
  std::vector<std::uint8_t> channel;
  for (const char c : std::string("/avar/channel/neck")) channel.push_back(static_cast<std::uint8_t>(c));
  channel.insert(channel.end(), {0, 0, ',', 'd', 0, 0, 0xC0, 0x28, 0x80, 0, 0, 0, 0, 0});
  const auto channel_posts = osc_posts_of(channel, &counters);
  ASSERT_EQ(channel_posts.size(), 1u);
  EXPECT_EQ(channel_posts[0].name, "channel/neck");
  EXPECT_EQ(channel_posts[0].value, -12.25);
}

TEST(OscPacket, MalformedDatagramsAreCountedAndIgnored) {
  const std::vector<std::vector<std::uint8_t>> bad{
      {},
      {'h', 'e', 'l', 'l', 'o'},
      {'/', 'a', 0, 0},                                 // no type tags
      {'/', 'a', 0, 0, ',', 'f', 0, 0},                 // a float announced, none there
      {'/', 'a', 0, 0, ',', 'f', 0, 0, 0x3F, 0x00},     // half a float
      {'#', 'b', 'u', 'n', 'd', 'l', 'e', 0, 0, 0, 0},  // a bundle shorter than its time tag
  };
  for (const auto& packet : bad) {
    InputCounters counters;
    EXPECT_TRUE(osc_posts_of(packet, &counters).empty());
    EXPECT_EQ(counters.messages, 1u);
    EXPECT_EQ(counters.ignored, 1u);
  }
}

TEST(OscPacket, BundlesAreUnpackedNestedAndChecked) {
  const lo_bundle outer = lo_bundle_new(LO_TT_IMMEDIATE);
  const lo_bundle inner = lo_bundle_new(LO_TT_IMMEDIATE);
  const auto add = [](lo_bundle b, const char* path, auto fill) {
    const lo_message m = lo_message_new();
    fill(m);
    lo_bundle_add_message(b, path, m);
  };
  add(outer, "/avar/control/a", [](lo_message m) { lo_message_add_float(m, 0.1f); });
  add(outer, "/avar/control/b", [](lo_message m) { lo_message_add_string(m, "no"); });
  add(inner, "/avar/control/c", [](lo_message m) { lo_message_add_int32(m, 3); });
  add(inner, "/avar/channel/d", [](lo_message m) { lo_message_add_double(m, -4.5); });
  lo_bundle_add_bundle(outer, inner);
  std::size_t size = 0;
  void* data = lo_bundle_serialise(outer, nullptr, &size);
  std::vector<std::uint8_t> packet(static_cast<std::uint8_t*>(data), static_cast<std::uint8_t*>(data) + size);
  std::free(data);
  lo_bundle_free_recursive(outer);

  InputCounters counters;
  auto posts = osc_posts_of(packet, &counters);
  ASSERT_EQ(posts.size(), 3u);
  EXPECT_EQ(posts[0].name, "a");
  EXPECT_FLOAT_EQ(static_cast<float>(posts[0].value), 0.1f);
  EXPECT_EQ(posts[1].name, "c");
  EXPECT_EQ(posts[1].value, 3.0);
  EXPECT_EQ(posts[2].name, "channel/d");
  EXPECT_EQ(posts[2].value, -4.5);
  EXPECT_EQ(counters.messages, 4u);
  EXPECT_EQ(counters.ignored, 1u);

  // An element whose size runs past the datagram: what came before it stands, it is ignored.
  packet.erase(packet.end() - 4, packet.end());
  posts = osc_posts_of(packet, &counters);
  EXPECT_EQ(posts.size(), 1u);  // the nested bundle's last message is cut: that bundle is one bad element
  EXPECT_EQ(counters.messages, 3u);
  EXPECT_EQ(counters.ignored, 2u);
}

/// Sends raw bytes to 127.0.0.1:port from a plain UDP socket.
void osc_send_raw(std::uint16_t port, const std::string& bytes) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  ASSERT_GE(fd, 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(port);
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  EXPECT_EQ(::sendto(fd, bytes.data(), bytes.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof to),
            static_cast<ssize_t>(bytes.size()));
  ::close(fd);
}

std::int64_t osc_test_now_ns() { return monotonic_ns(); }

TEST(OscInputLoopback, DeliversExactlyTheGoodMessagesInOrder) {
  RecordingControlSink sink;
  OscInput input("127.0.0.1", 0);
  EXPECT_EQ(input.bound_address(), "");
  input.start(sink);
  const std::uint16_t port = input.bound_port();
  ASSERT_NE(port, 0);
  EXPECT_EQ(input.bound_address(), "127.0.0.1:" + std::to_string(port));
  EXPECT_EQ(input.describe(), "OSC on udp 127.0.0.1:" + std::to_string(port));

  const std::int64_t before = osc_test_now_ns();
  const OscSender to(port);
  ASSERT_EQ(lo_send(to.address(), "/avar/control/jaw", "f", 0.5f), 28);
  lo_send(to.address(), "/avar/control/jaw", "s", "half");  // not a number
  lo_send(to.address(), "/avar/channel/neck", "d", -12.5);
  lo_send(to.address(), "/nowhere", "f", 1.0f);  // not ours
  lo_send(to.address(), "/avar/control/blink", "T");
  lo_send(to.address(), "/avar/control/jaw", "f", std::nanf(""));
  lo_send(to.address(), "/avar/control/jaw", "ff", 0.1f, 0.2f);  // two numbers
  const lo_bundle bundle = lo_bundle_new(LO_TT_IMMEDIATE);
  lo_message eye = lo_message_new();
  lo_message_add_int32(eye, 1);
  lo_bundle_add_message(bundle, "/avar/control/eye.x", eye);
  lo_message bang = lo_message_new();
  lo_message_add_float(bang, 1.0f);
  lo_bundle_add_message(bundle, "/avar/control/bang!", bang);  // '!' is not a name's
  lo_send_bundle(to.address(), bundle);
  lo_bundle_free_recursive(bundle);
  osc_send_raw(port, "not OSC at all");
  lo_send(to.address(), "/avar/control/jaw", "h", static_cast<std::int64_t>(2));

  ASSERT_TRUE(eventually([&] { return input.counters().messages >= 11; }))
      << "only " << input.counters().messages << " of 11 messages arrived";
  const std::int64_t after = osc_test_now_ns();
  const InputCounters counters = input.counters();
  EXPECT_EQ(counters.messages, 11u);
  EXPECT_EQ(counters.ignored, 6u);

  const auto posts = sink.posts();
  const std::vector<std::pair<std::string, double>> expected{
      {"jaw", 0.5}, {"channel/neck", -12.5}, {"blink", 1.0}, {"eye.x", 1.0}, {"jaw", 2.0}};
  ASSERT_EQ(posts.size(), expected.size());
  std::int64_t previous = before;
  for (std::size_t i = 0; i < posts.size(); ++i) {
    EXPECT_EQ(posts[i].name, expected[i].first);
    EXPECT_EQ(posts[i].value, expected[i].second);
    EXPECT_FALSE(posts[i].bipolar);
    EXPECT_GE(posts[i].arrived_ns, previous);  // CLOCK_MONOTONIC, in arrival order
    EXPECT_LE(posts[i].arrived_ns, after);
    previous = posts[i].arrived_ns;
  }
  input.stop();
  EXPECT_EQ(input.bound_address(), "");
}

TEST(OscInputLoopback, ListensOnLoopbackUnlessToldOtherwise) {
  RecordingControlSink sink;
  OscInput loopback("localhost", 0);
  loopback.start(sink);
  EXPECT_EQ(loopback.bound_address(), "127.0.0.1:" + std::to_string(loopback.bound_port()));
  OscInput everywhere("0.0.0.0", 0);
  everywhere.start(sink);
  EXPECT_EQ(everywhere.bound_address(), "0.0.0.0:" + std::to_string(everywhere.bound_port()));
  EXPECT_THROW(OscInput("example.com", 0), std::invalid_argument);
  EXPECT_THROW(OscInput("::1", 0), std::invalid_argument);
}

TEST(OscInputLoopback, AnAddressInUseIsNamed) {
  RecordingControlSink sink;
  OscInput first("127.0.0.1", 0);
  first.start(sink);
  const std::string port = std::to_string(first.bound_port());
  OscInput second("127.0.0.1", first.bound_port());
  try {
    second.start(sink);
    FAIL() << "a second listener on 127.0.0.1:" << port << " started";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("OSC: cannot listen on 127.0.0.1:" + port + " (address in use", 0), 0u) << e.what();
  }
  OscInput everywhere("0.0.0.0", first.bound_port());
  EXPECT_THROW(everywhere.start(sink), std::runtime_error);
  EXPECT_EQ(second.bound_address(), "");
}

TEST(OscInputLoopback, StartAndStopAreIdempotent) {
  RecordingControlSink sink;
  RecordingControlSink other;
  OscInput input("127.0.0.1", 0);
  input.stop();  // never started: nothing to do
  input.start(sink);
  const std::uint16_t port = input.bound_port();
  input.start(sink);  // same sink: no-op
  EXPECT_EQ(input.bound_port(), port);
  EXPECT_THROW(input.start(other), std::logic_error);
  {
    const OscSender to(port);
    lo_send(to.address(), "/avar/control/a", "f", 0.25f);
    ASSERT_TRUE(eventually([&] { return input.counters().messages == 1; }));
  }
  input.stop();
  input.stop();
  EXPECT_EQ(sink.posts().size(), 1u);

  // Started again, it listens again (port 0: wherever the system says now).
  input.start(other);
  const OscSender to(input.bound_port());
  lo_send(to.address(), "/avar/control/b", "i", 1);
  ASSERT_TRUE(eventually([&] { return input.counters().messages == 2; }));
  ASSERT_EQ(other.posts().size(), 1u);
  EXPECT_EQ(other.posts()[0].name, "b");
  EXPECT_EQ(sink.posts().size(), 1u);
}

TEST(OscInputLoopback, ManySendersAtOnce) {
  RecordingControlSink sink;
  OscInput input("127.0.0.1", 0);
  input.start(sink);
  constexpr int kSenders = 4;
  constexpr int kEach = 50;
  std::vector<std::thread> senders;
  for (int s = 0; s < kSenders; ++s)
    senders.emplace_back([&, s] {
      const OscSender to(input.bound_port());
      const std::string path = "/avar/control/s" + std::to_string(s);
      for (int i = 0; i < kEach; ++i) {
        lo_send(to.address(), path.c_str(), "i", i);
        if (i % 10 == 9) std::this_thread::sleep_for(std::chrono::milliseconds(1));  // the socket's buffer is finite
      }
    });
  for (auto& t : senders) t.join();
  ASSERT_TRUE(eventually([&] { return input.counters().messages == kSenders * kEach; }))
      << input.counters().messages << " of " << kSenders * kEach;
  const auto posts = sink.posts();
  ASSERT_EQ(posts.size(), static_cast<std::size_t>(kSenders * kEach));
  std::vector<int> next(kSenders, 0);
  for (const auto& p : posts) {
    const int s = p.name.back() - '0';
    EXPECT_EQ(p.value, next[s]++);  // each sender's messages in its order
  }
}

}  // namespace
}  // namespace avar::inputs
