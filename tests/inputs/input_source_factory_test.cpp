// Input URIs: what each form makes, what a bad one is told, and a named source's control names.
#include "avar/inputs/input_source_factory.hpp"

#include <lo/lo.h>

#include <gtest/gtest.h>

#include "../support/osc_sender.hpp"
#include "../support/recording_control_sink.hpp"

#include <stdexcept>
#include <string>

#include "avar/inputs/osc_input.hpp"
#include "avar/inputs/prefixed_input_source.hpp"

namespace avar::inputs {
namespace {

std::string factory_describe(std::string_view uri) { return make_input_source(uri)->describe(); }

TEST(InputSourceFactory, AcceptedForms) {
  EXPECT_EQ(factory_describe("osc://:9000"), "OSC on udp 127.0.0.1:9000");
  EXPECT_EQ(factory_describe("osc://127.0.0.1:9001"), "OSC on udp 127.0.0.1:9001");
  EXPECT_EQ(factory_describe("osc://localhost:9002"), "OSC on udp 127.0.0.1:9002");
  EXPECT_EQ(factory_describe("osc://0.0.0.0:9003"), "OSC on udp 0.0.0.0:9003");
  EXPECT_EQ(factory_describe("osc://192.168.1.20:8000/"), "OSC on udp 192.168.1.20:8000");
  EXPECT_EQ(factory_describe("osc://"), "OSC on udp 127.0.0.1:9000");
  EXPECT_EQ(factory_describe("osc://0.0.0.0"), "OSC on udp 0.0.0.0:9000");
  EXPECT_EQ(factory_describe("osc://:0"), "OSC on udp 127.0.0.1:0");
  EXPECT_EQ(factory_describe("midi:nano"), "MIDI 'nano'");
  EXPECT_EQ(factory_describe("midi:1"), "MIDI '1'");
  EXPECT_EQ(factory_describe("midi:Launch Control XL:0"), "MIDI 'Launch Control XL:0'");
  EXPECT_EQ(factory_describe("midi:a=b"), "MIDI 'a=b'");  // '=' after the scheme is the port's
  EXPECT_EQ(factory_describe("pad=osc://:9000"), "pad: OSC on udp 127.0.0.1:9000");
  EXPECT_EQ(factory_describe("left_hand-2=midi:nano"), "left_hand-2: MIDI 'nano'");
  EXPECT_EQ(factory_describe("hid:054c:09cc"), "HID 054c:09cc");
  EXPECT_EQ(factory_describe("pad=hid:046d:c216:AB12"), "pad: HID 046d:c216 serial AB12");
  const auto named = make_input_source("pad=osc://:9000");
  auto* prefixed = dynamic_cast<PrefixedInputSource*>(named.get());
  ASSERT_NE(prefixed, nullptr);
  EXPECT_EQ(prefixed->prefix(), "pad");
  EXPECT_NE(dynamic_cast<OscInput*>(&prefixed->inner()), nullptr);
}

TEST(InputSourceFactory, BadUrisTeachTheForms) {
  for (const char* uri : {"", "osc:9000", "osc://:abc", "osc://:70000", "osc://:-1", "osc://:9000/path", "osc://example.com:9000",
                          "osc://[::1]:9000", "midi:", "midi", "udp://:9000", "hid:054c", "hid:zz:09cc",
                          "hid:", "bad name=osc://:1", "=osc://:1", "pad=", "pad=pad=osc://:1"}) {
    SCOPED_TRACE(uri);
    try {
      make_input_source(uri);
      ADD_FAILURE() << "accepted";
    } catch (const std::invalid_argument& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind("input '" + std::string(uri) + "': ", 0), 0u) << message;
      EXPECT_NE(message.find("expected osc://HOST:PORT"), std::string::npos) << message;
      EXPECT_NE(message.find("midi:PORT"), std::string::npos) << message;
      EXPECT_NE(message.find("hid:VID:PID[:SERIAL]"), std::string::npos) << message;
      EXPECT_NE(message.find("NAME=URI"), std::string::npos) << message;
    }
  }
}

TEST(InputSourceFactory, ANamedSourceNamesItsControls) {
  avar::testing::RecordingControlSink sink;
  const auto source = make_input_source("pad=osc://:0");
  source->start(sink);
  auto& osc = dynamic_cast<OscInput&>(dynamic_cast<PrefixedInputSource&>(*source).inner());
  EXPECT_EQ(source->describe(), "pad: OSC on udp 127.0.0.1:" + std::to_string(osc.bound_port()));
  avar::testing::OscSender to(osc.bound_port());
  ASSERT_TRUE(to.send("/avar/control/jaw", 0.75f));
  lo_send(to.address(), "/avar/control/jaw", "s", "no");
  ASSERT_TRUE(to.send("/avar/channel/neck", 10.0f));
  ASSERT_TRUE(avar::testing::eventually([&] { return source->counters().messages == 3; }));
  source->stop();
  const auto posts = sink.posts();
  ASSERT_EQ(posts.size(), 2u);
  EXPECT_EQ(posts[0].name, "pad.jaw");
  EXPECT_EQ(posts[0].value, 0.75);
  EXPECT_EQ(posts[1].name, "channel/neck");  // a channel of the rig: not the pad's to name
  EXPECT_EQ(posts[1].value, 10.0);
  EXPECT_EQ(source->counters().ignored, 1u);
}

/// A source that posts what the test tells it to, on the test's thread.
class FactoryTestEchoSource final : public InputSource {
 public:
  void start(ControlSink& sink) override { sink_ = &sink; }
  void stop() noexcept override { sink_ = nullptr; }
  std::string describe() const override { return "echo"; }
  InputCounters counters() const noexcept override { return {7, 1}; }
  void emit(std::string_view control) { sink_->post(control, 0.5, true, 9); }

 private:
  ControlSink* sink_ = nullptr;
};

TEST(PrefixedInputSource, PrefixesAllButChannelsAndCountsNamesTooLong) {
  auto inner = std::make_unique<FactoryTestEchoSource>();
  FactoryTestEchoSource& echo = *inner;
  PrefixedInputSource source("x", std::move(inner));
  avar::testing::RecordingControlSink sink;
  source.start(sink);
  echo.emit("ch1.bend");
  echo.emit("channel/jaw");
  const std::string longest(PrefixedInputSource::kMaxName - 2, 'n');
  echo.emit(longest);
  echo.emit(longest + "n");
  const auto posts = sink.posts();
  ASSERT_EQ(posts.size(), 3u);
  EXPECT_EQ(posts[0].name, "x.ch1.bend");
  EXPECT_EQ(posts[0].value, 0.5);
  EXPECT_TRUE(posts[0].bipolar);
  EXPECT_EQ(posts[0].arrived_ns, 9);
  EXPECT_EQ(posts[1].name, "channel/jaw");
  EXPECT_EQ(posts[2].name, "x." + longest);
  EXPECT_EQ(source.counters().messages, 7u);
  EXPECT_EQ(source.counters().ignored, 2u);
  EXPECT_EQ(source.describe(), "x: echo");
}

}  // namespace
}  // namespace avar::inputs
