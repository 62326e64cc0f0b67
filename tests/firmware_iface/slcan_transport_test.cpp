// SlcanTransport against the simulated Lawicel adapter: over an in-memory wire (SimWire) and over
// a real pseudo-terminal (PtyDeviceHost + SerialTransport), with a responder node on the bus;
// noise, refusals, bus-off and error frames on the line.
#include "avar/firmware_iface/slcan_transport.hpp"

#include <gtest/gtest.h>

#include <deque>
#include <functional>
#include <string>
#include <vector>

#include "../support/can_responder_node.hpp"
#include "avar/core/input_error.hpp"
#include "avar/firmware_iface/serial_transport.hpp"
#include "avar/sim/faulty_device.hpp"
#include "avar/sim/pty_device_host.hpp"
#include "avar/sim/reply_queue.hpp"
#include "avar/sim/sim_slcan_adapter.hpp"
#include "avar/sim/sim_wire.hpp"

namespace avar::firmware_iface {
namespace {

using namespace std::chrono_literals;
using test::CanResponderNode;

std::string slcan_string(const std::vector<std::uint8_t>& bytes) { return {bytes.begin(), bytes.end()}; }

/// Sits between the wire and the adapter and lets a test put raw bytes on the line before the
/// adapter's next replies (noise, a malformed reply).
class SlcanLineNoise final : public sim::ByteDevice {
 public:
  explicit SlcanLineNoise(sim::ByteDevice& inner) : inner_(inner) {}
  void receive(std::span<const std::uint8_t> bytes) override { inner_.receive(bytes); }
  std::size_t take_replies(std::span<std::uint8_t> out) override {
    if (!noise_.empty()) return sim::take_from(noise_, out);
    return inner_.take_replies(out);
  }
  void advance(double dt_s) override { inner_.advance(dt_s); }
  std::uint64_t bytes_received() const override { return inner_.bytes_received(); }
  void inject(const std::string& bytes) { noise_.insert(noise_.end(), bytes.begin(), bytes.end()); }

 private:
  sim::ByteDevice& inner_;
  std::deque<std::uint8_t> noise_;
};

/// An adapter answering each command line through a test's function (text to send back).
class SlcanScriptedAdapter final : public sim::ByteDevice {
 public:
  explicit SlcanScriptedAdapter(std::function<std::string(const std::string&)> answer) : answer_(std::move(answer)) {}
  void receive(std::span<const std::uint8_t> bytes) override {
    for (std::uint8_t b : bytes) {
      ++received_;
      if (b != '\r') {
        line_.push_back(static_cast<char>(b));
        continue;
      }
      commands.push_back(line_);
      const std::string a = answer_(line_);
      replies_.insert(replies_.end(), a.begin(), a.end());
      line_.clear();
    }
  }
  std::size_t take_replies(std::span<std::uint8_t> out) override { return sim::take_from(replies_, out); }
  void advance(double) override {}
  std::uint64_t bytes_received() const override { return received_; }
  std::vector<std::string> commands;

 private:
  std::function<std::string(const std::string&)> answer_;
  std::string line_;
  std::deque<std::uint8_t> replies_;
  std::uint64_t received_ = 0;
};

/// The adapter with one responder (0x123 -> 0x124) on a 1 Mbit/s bus, a wire, and the transport.
struct SlcanRig {
  CanResponderNode node{0x123};
  sim::SimSlcanAdapter adapter;
  SlcanLineNoise noise{adapter};
  sim::SimWire* wire = nullptr;
  std::unique_ptr<SlcanTransport> transport;

  explicit SlcanRig(sim::SimSlcanConfig config = {}) : adapter(std::move(config), {&node}) {
    auto w = std::make_unique<sim::SimWire>(noise, 1'000'000, 0, "sim-tty");
    wire = w.get();
    transport = std::make_unique<SlcanTransport>(std::move(w), 1'000'000);
  }
  Status receive(CanFrame* f, std::chrono::nanoseconds timeout = 10ms) {
    return transport->receive(f, transport->now() + timeout);
  }
};

std::string slcan_open_error(sim::ByteDevice& device, int bitrate = 1'000'000) {
  try {
    SlcanTransport t(std::make_unique<sim::SimWire>(device, 1'000'000, 0, "/dev/ttyTEST"), bitrate);
    return "";
  } catch (const InputError& e) {
    return e.what();
  }
}

TEST(SlcanTransport, OpensWithCloseBitrateVersionSerialOpen) {
  SlcanScriptedAdapter scripted([](const std::string& c) -> std::string {
    if (c == "C") return "\a";  // already closed: a Lawicel adapter refuses, which is fine
    if (c == "V") return "V1013\r";
    if (c == "N") return "NA123\r";
    return "\r";
  });
  {
    SlcanTransport t(std::make_unique<sim::SimWire>(scripted, 1'000'000, 0, "/dev/ttyACM0"), 800'000);
    EXPECT_EQ(scripted.commands, (std::vector<std::string>{"C", "S7", "V", "N", "O"}));
    EXPECT_EQ(t.version(), "V1013");
    EXPECT_EQ(t.serial_number(), "NA123");
    EXPECT_EQ(t.name(), "SLCAN on /dev/ttyACM0");
    EXPECT_EQ(t.bitrate(), 800'000);
  }
  EXPECT_EQ(scripted.commands.back(), "C");  // the destructor closes the adapter

  SlcanRig rig;
  EXPECT_TRUE(rig.adapter.is_open());
  EXPECT_EQ(rig.adapter.bitrate_code(), 8);
  EXPECT_EQ(rig.transport->version(), "V1013");
  rig.transport.reset();
  EXPECT_FALSE(rig.adapter.is_open());
}

TEST(SlcanTransport, AnAdapterThatRefusesVersionAndSerialIsFine) {
  SlcanScriptedAdapter scripted([](const std::string& c) -> std::string { return c == "V" || c == "N" ? "\a" : "\r"; });
  SlcanTransport t(std::make_unique<sim::SimWire>(scripted), 500'000);
  EXPECT_EQ(t.version(), "");
  EXPECT_EQ(t.serial_number(), "");
}

TEST(SlcanTransport, OpenProblemsNameThePortAndTheStep) {
  SlcanScriptedAdapter refuses_bitrate([](const std::string& c) -> std::string { return c[0] == 'S' ? "\a" : "\r"; });
  const std::string bitrate = slcan_open_error(refuses_bitrate);
  EXPECT_NE(bitrate.find("/dev/ttyTEST"), std::string::npos) << bitrate;
  EXPECT_NE(bitrate.find("S8 (set the bitrate to 1000000 bit/s)"), std::string::npos) << bitrate;
  EXPECT_NE(bitrate.find("BEL"), std::string::npos) << bitrate;

  SlcanScriptedAdapter refuses_open([](const std::string& c) -> std::string { return c == "O" ? "\a" : "\r"; });
  const std::string open = slcan_open_error(refuses_open);
  EXPECT_NE(open.find("O (open)"), std::string::npos) << open;

  SlcanScriptedAdapter silent([](const std::string&) -> std::string { return ""; });
  const std::string none = slcan_open_error(silent);
  EXPECT_NE(none.find("/dev/ttyTEST"), std::string::npos) << none;
  EXPECT_NE(none.find("no answer to C (close)"), std::string::npos) << none;
  EXPECT_NE(none.find("SLCAN adapter"), std::string::npos) << none;

  SlcanScriptedAdapter fine([](const std::string&) -> std::string { return "\r"; });
  const std::string rate = slcan_open_error(fine, 750'000);
  EXPECT_NE(rate.find("750000 bit/s has no Sn code"), std::string::npos) << rate;
  EXPECT_TRUE(fine.commands.empty());  // refused before a byte was sent
}

TEST(SlcanTransport, FramesGoOutAndTheRespondersRepliesComeBack) {
  SlcanRig rig;
  const CanFrame request = can_data_frame(0x123, std::vector<std::uint8_t>{1, 2, 3, 4, 5, 6, 7, 8});
  ASSERT_EQ(rig.transport->send(std::span(&request, 1)), Status::ok);
  ASSERT_EQ(rig.node.heard.size(), 1u);
  EXPECT_EQ(rig.node.heard[0], request);
  CanFrame reply;
  ASSERT_EQ(rig.receive(&reply), Status::ok);
  EXPECT_EQ(reply.id, 0x124u);
  EXPECT_EQ(reply.payload().size(), 8u);
  EXPECT_EQ(reply.data[7], 8);
  EXPECT_EQ(reply.timestamp, rig.transport->now());  // stamped when its line was read
  const FrameCounters c = rig.transport->counters();
  EXPECT_EQ(c.frames_sent, 1u);
  EXPECT_EQ(c.frames_received, 1u);
  EXPECT_EQ(c.malformed, 0u);
  EXPECT_GT(c.bytes_received, 0u);
}

TEST(SlcanTransport, SendWritesEveryLineInOneWrite) {
  SlcanRig rig;
  const std::uint64_t writes = rig.wire->writes();
  const std::array<CanFrame, 3> frames{can_data_frame(0x010, std::vector<std::uint8_t>{0xAB}), can_remote_frame(0x123, 2),
                                       can_data_frame(0x12345678, std::vector<std::uint8_t>{1, 2}, true)};
  ASSERT_EQ(rig.transport->send(frames), Status::ok);
  EXPECT_EQ(rig.wire->writes(), writes + 1);
  EXPECT_EQ(slcan_string(rig.wire->last_write()),
            "t0101AB\rr1232\rT123456782"
            "0102\r");
  EXPECT_EQ(rig.adapter.transmitted(), 3u);
  CanFrame reply;
  ASSERT_EQ(rig.receive(&reply), Status::ok);  // the RTR's answer: bytes 0, 1
  EXPECT_EQ(reply, can_data_frame(0x124, std::vector<std::uint8_t>{0, 1}));
}

TEST(SlcanTransport, InvalidFramesAreRefusedBeforeAnythingIsWritten) {
  SlcanRig rig;
  const std::uint64_t writes = rig.wire->writes();
  CanFrame error_frame;
  error_frame.error = true;
  const std::array<CanFrame, 2> frames{can_data_frame(0x1, std::vector<std::uint8_t>{}),
                                       can_data_frame(0x800, std::vector<std::uint8_t>{})};
  EXPECT_EQ(rig.transport->send(frames), Status::out_of_range);
  EXPECT_EQ(rig.transport->send(std::span(&error_frame, 1)), Status::out_of_range);
  EXPECT_EQ(rig.wire->writes(), writes);
}

TEST(SlcanTransport, ManyFramesOutgrowingTheBufferAreAllSent) {
  SlcanRig rig;
  std::vector<CanFrame> frames(200, can_data_frame(0x12345678, std::vector<std::uint8_t>(8, 0x5A), true));
  ASSERT_EQ(rig.transport->send(frames), Status::ok);
  EXPECT_EQ(rig.adapter.transmitted(), 200u);
  EXPECT_EQ(rig.transport->counters().bytes_sent, 11u + 200u * 27u);  // after C, S8, V, N, O
}

TEST(SlcanTransport, AcksAndBareCrRepliesAreSkipped) {
  sim::SimSlcanConfig config;
  config.transmit_acks = true;
  SlcanRig rig(config);
  const std::array<CanFrame, 2> frames{can_data_frame(0x123, std::vector<std::uint8_t>{9}),
                                       can_data_frame(0x1234, std::vector<std::uint8_t>{}, true)};
  ASSERT_EQ(rig.transport->send(frames), Status::ok);
  CanFrame reply;
  ASSERT_EQ(rig.receive(&reply), Status::ok);
  EXPECT_EQ(reply, can_data_frame(0x124, std::vector<std::uint8_t>{9}));
  EXPECT_EQ(rig.receive(&reply), Status::timeout);
  EXPECT_EQ(rig.transport->counters().malformed, 0u);
}

TEST(SlcanTransport, AdapterTimestampsAreReadAndTheFrameIsStampedOnTheHostClock) {
  SlcanRig rig;
  ASSERT_EQ(rig.transport->port().write(std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>("Z1\r"), 3)),
            Status::ok);
  EXPECT_TRUE(rig.adapter.timestamps());
  rig.node.queue(can_data_frame(0x300, std::vector<std::uint8_t>{7}));
  rig.adapter.advance(0.25);
  CanFrame f;
  ASSERT_EQ(rig.receive(&f), Status::ok);  // the Z1 answer (a bare CR) is skipped
  EXPECT_EQ(f, can_data_frame(0x300, std::vector<std::uint8_t>{7}));
  EXPECT_EQ(f.timestamp, rig.transport->now());
}

TEST(SlcanTransport, ReceiveTimesOutAtTheDeadlineOnTheWiresClock) {
  SlcanRig rig;
  const auto deadline = rig.transport->now() + 5ms;
  CanFrame f;
  EXPECT_EQ(rig.transport->receive(&f, deadline), Status::timeout);
  EXPECT_GE(rig.transport->now() + 1us, deadline);  // the wire's clock is in double seconds
  EXPECT_LT(rig.transport->now(), deadline + 2ms);
  EXPECT_EQ(rig.transport->receive(&f, rig.transport->now()), Status::timeout);  // a deadline now: one look
}

TEST(SlcanTransport, NoiseAndMalformedRepliesAreCountedAndSkipped) {
  SlcanRig rig;
  // Garbage before a frame, a truncated frame, bad hex, a line far too long, and a stray BEL.
  rig.noise.inject("\x55\xAA\x13\rt12\rt12311G\r" + std::string(100, 'x') + "\r\a");
  const CanFrame request = can_data_frame(0x123, std::vector<std::uint8_t>{42});
  ASSERT_EQ(rig.transport->send(std::span(&request, 1)), Status::ok);
  CanFrame reply;
  ASSERT_EQ(rig.receive(&reply), Status::ok);
  EXPECT_EQ(reply, can_data_frame(0x124, std::vector<std::uint8_t>{42}));
  EXPECT_EQ(rig.transport->counters().malformed, 4u);
  EXPECT_EQ(rig.transport->refused(), 1u);
  // Noise glued to the front of a line spoils that line only: the next one decodes.
  rig.noise.inject("t1241");
  rig.node.queue(can_data_frame(0x222, std::vector<std::uint8_t>{1}));
  rig.node.queue(can_data_frame(0x223, std::vector<std::uint8_t>{2}));
  rig.adapter.advance(0);
  ASSERT_EQ(rig.receive(&reply), Status::ok);
  EXPECT_EQ(reply, can_data_frame(0x223, std::vector<std::uint8_t>{2}));
  EXPECT_EQ(rig.transport->counters().malformed, 5u);
}

TEST(SlcanTransport, ARandomlyCorruptedLineNeverWedgesTheTransport) {
  CanResponderNode node{0x123};
  sim::SimSlcanAdapter adapter({}, {&node});
  sim::FaultyDevice faulty(adapter, {});
  SlcanTransport t(std::make_unique<sim::SimWire>(faulty), 1'000'000);
  sim::FaultPlan plan;
  plan.corrupt_reply = 0.3;
  plan.drop_reply = 0.05;
  plan.seed = 7;
  faulty.set_plan(plan);
  int received = 0;
  for (std::uint8_t i = 0; i < 200; ++i) {
    const CanFrame request = can_data_frame(0x123, std::vector<std::uint8_t>{i, 0x55, 0xAA});
    ASSERT_EQ(t.send(std::span(&request, 1)), Status::ok);
    CanFrame reply;
    while (t.receive(&reply, t.now() + 2ms) == Status::ok) ++received;
  }
  EXPECT_GT(t.counters().malformed, 0u);
  EXPECT_GT(received, 50);
  faulty.set_plan({});
  const CanFrame request = can_data_frame(0x123, std::vector<std::uint8_t>{1});
  ASSERT_EQ(t.send(std::span(&request, 1)), Status::ok);
  CanFrame reply;
  ASSERT_EQ(t.receive(&reply, t.now() + 5ms), Status::ok);
  EXPECT_EQ(reply, can_data_frame(0x124, std::vector<std::uint8_t>{1}));
}

TEST(SlcanTransport, BusOffReachesTheHostAndReopenRecovers) {
  SlcanRig rig;
  rig.adapter.bus().inject_bus_off();
  rig.adapter.flush_bus();
  CanFrame f;
  ASSERT_EQ(rig.receive(&f), Status::ok);
  EXPECT_TRUE(f.error);
  EXPECT_EQ(f.id, kCanErrorBusOff);
  EXPECT_EQ(rig.transport->counters().bus_off, 1u);
  EXPECT_EQ(rig.transport->counters().error_frames, 1u);
  const CanFrame request = can_data_frame(0x123, std::vector<std::uint8_t>{1});
  EXPECT_EQ(rig.transport->send(std::span(&request, 1)), Status::io_error);
  ASSERT_EQ(rig.transport->reopen(), Status::ok);
  EXPECT_FALSE(rig.adapter.bus().host_bus_off());
  ASSERT_EQ(rig.transport->send(std::span(&request, 1)), Status::ok);
  ASSERT_EQ(rig.receive(&f), Status::ok);
  EXPECT_EQ(f.id, 0x124u);
}

TEST(SlcanTransport, ReopenFailsWhileTheWireIsUnpluggedAndSaysWhy) {
  SlcanRig rig;
  rig.wire->set_connected(false);
  const CanFrame request = can_data_frame(0x123, std::vector<std::uint8_t>{1});
  EXPECT_EQ(rig.transport->send(std::span(&request, 1)), Status::io_error);
  EXPECT_EQ(rig.transport->reopen(), Status::io_error);
  rig.wire->set_connected(true);
  ASSERT_EQ(rig.transport->reopen(), Status::ok);
  EXPECT_EQ(rig.transport->send(std::span(&request, 1)), Status::ok);
}

TEST(SlcanTransport, ErrorFramesReachTheHostByClass) {
  SlcanRig rig;
  rig.adapter.bus().inject_error(kCanErrorPassive | kCanErrorAck);
  rig.adapter.flush_bus();
  CanFrame f;
  ASSERT_EQ(rig.receive(&f), Status::ok);
  EXPECT_TRUE(f.error);
  EXPECT_EQ(f.id, kCanErrorPassive);  // the state line
  ASSERT_EQ(rig.receive(&f), Status::ok);
  EXPECT_EQ(f.id, kCanErrorAck);  // the error line
  EXPECT_EQ(rig.transport->counters().error_frames, 2u);
  EXPECT_EQ(rig.transport->counters().bus_off, 0u);
}

TEST(SlcanTransport, StatusFlagsAreReadAndFramesMeanwhileKept) {
  sim::SimSlcanConfig config;
  config.linux_error_lines = false;  // a plain Lawicel adapter: errors only in F
  SlcanRig rig(config);
  rig.adapter.bus().inject_error(kCanErrorWarning);
  rig.node.queue(can_data_frame(0x321, std::vector<std::uint8_t>{3}));
  rig.adapter.advance(0);
  std::uint8_t flags = 0;
  std::uint32_t classes = 0;
  ASSERT_EQ(rig.transport->read_status(&flags, &classes), Status::ok);
  EXPECT_EQ(flags, slcan::kErrorWarning);
  EXPECT_EQ(classes, kCanErrorWarning);
  CanFrame f;
  ASSERT_EQ(rig.receive(&f, 0ms), Status::ok);  // the frame read before the F reply
  EXPECT_EQ(f, can_data_frame(0x321, std::vector<std::uint8_t>{3}));
  ASSERT_EQ(rig.transport->read_status(&flags, &classes), Status::ok);
  EXPECT_EQ(flags, 0);  // cleared by reading
}

TEST(SlcanTransport, ListenOnlyOpensWithLAndTheAdapterRefusesTransmits) {
  CanResponderNode node{0x123};
  sim::SimSlcanAdapter adapter({}, {&node});
  SlcanTransportConfig config;
  config.listen_only = true;
  SlcanTransport t(std::make_unique<sim::SimWire>(adapter), 1'000'000, config);
  EXPECT_TRUE(adapter.listen_only());
  const CanFrame request = can_data_frame(0x123, std::vector<std::uint8_t>{1});
  ASSERT_EQ(t.send(std::span(&request, 1)), Status::ok);  // written; the adapter answers BEL
  CanFrame f;
  EXPECT_EQ(t.receive(&f, t.now() + 2ms), Status::timeout);
  EXPECT_EQ(t.refused(), 1u);
  EXPECT_TRUE(node.heard.empty());
}

TEST(SlcanTransport, EndToEndThroughAPseudoTerminal) {
  CanResponderNode node{0x123};
  sim::SimSlcanAdapter adapter({}, {&node});
  sim::PtyDeviceHost host(adapter, sim::PtyDeviceHost::Clock::stepped);
  SlcanTransport t(std::make_unique<SerialTransport>(host.slave_path(), 115200), 1'000'000);
  EXPECT_EQ(t.name(), "SLCAN on " + host.slave_path());
  EXPECT_EQ(t.version(), "V1013");
  for (std::uint8_t i = 0; i < 16; ++i) {
    const CanFrame request = can_data_frame(0x123, std::vector<std::uint8_t>{i, 1, 2, 3, 4, 5, 6, 7});
    ASSERT_EQ(t.send(std::span(&request, 1)), Status::ok);
    CanFrame reply;
    ASSERT_EQ(t.receive(&reply, t.now() + 1s), Status::ok) << int(i);
    EXPECT_EQ(reply.id, 0x124u);
    EXPECT_EQ(reply.data[0], i);
  }
  // Unprompted lines: frames a node sends as the bus's time moves, and a bus-off.
  host.with_device([&](sim::ByteDevice& d) {
    node.queue(can_data_frame(0x050, std::vector<std::uint8_t>{5}));
    d.advance(0.001);
  });
  CanFrame f;
  ASSERT_EQ(t.receive(&f, t.now() + 1s), Status::ok);
  EXPECT_EQ(f, can_data_frame(0x050, std::vector<std::uint8_t>{5}));
  host.with_device([&](sim::ByteDevice&) {
    adapter.bus().inject_bus_off();
    adapter.flush_bus();
  });
  ASSERT_EQ(t.receive(&f, t.now() + 1s), Status::ok);
  EXPECT_TRUE(f.error);
  EXPECT_EQ(f.id, kCanErrorBusOff);
  ASSERT_EQ(t.reopen(), Status::ok);
  const CanFrame request = can_data_frame(0x123, std::vector<std::uint8_t>{0xEE});
  ASSERT_EQ(t.send(std::span(&request, 1)), Status::ok);
  ASSERT_EQ(t.receive(&f, t.now() + 1s), Status::ok);
  EXPECT_EQ(f, can_data_frame(0x124, std::vector<std::uint8_t>{0xEE}));
  EXPECT_EQ(t.counters().malformed, 0u);
}

}  // namespace
}  // namespace avar::firmware_iface
