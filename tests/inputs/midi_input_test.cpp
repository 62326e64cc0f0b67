// MIDI input: choosing a port by name or number everywhere; opening one through the ALSA
// sequencer where the machine has it (the test says what is missing elsewhere).
#include "avar/inputs/midi_input.hpp"

#include <rtmidi/RtMidi.h>

#include <gtest/gtest.h>

#include "../support/recording_control_sink.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace avar::inputs {
namespace {

const std::vector<std::string> kMidiTestPorts{"Midi Through:Midi Through Port-0 14:0", "nanoKONTROL2:nanoKONTROL2 MIDI 1 20:0",
                                              "Launch Control XL:Launch Control XL MIDI 1 24:0"};

std::string midi_select_error(std::string_view wanted, const std::vector<std::string>& ports) {
  try {
    select_midi_port(wanted, ports);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(MidiPortSelection, BySubstringAnyCaseOrByNumber) {
  EXPECT_EQ(select_midi_port("nano", kMidiTestPorts), 1u);
  EXPECT_EQ(select_midi_port("NANOkontrol", kMidiTestPorts), 1u);
  EXPECT_EQ(select_midi_port("launch control", kMidiTestPorts), 2u);
  EXPECT_EQ(select_midi_port("through", kMidiTestPorts), 0u);
  EXPECT_EQ(select_midi_port("2", kMidiTestPorts), 2u);
  EXPECT_EQ(select_midi_port("0", kMidiTestPorts), 0u);
  // A whole name wins over the other ports it is a part of.
  const std::vector<std::string> nested{"Pad", "Pad Pro", "Big Pad"};
  EXPECT_EQ(select_midi_port("pad", nested), 0u);
  EXPECT_EQ(select_midi_port("pad pro", nested), 1u);
}

TEST(MidiPortSelection, ErrorsListThePorts) {
  EXPECT_EQ(midi_select_error("korg", kMidiTestPorts),
            "no MIDI input port matching 'korg' (ports: 0: 'Midi Through:Midi Through Port-0 14:0', 1: "
            "'nanoKONTROL2:nanoKONTROL2 MIDI 1 20:0', 2: 'Launch Control XL:Launch Control XL MIDI 1 24:0')");
  EXPECT_EQ(midi_select_error("nano", {}), "no MIDI input port matching 'nano' (ports: none)");
  EXPECT_EQ(midi_select_error("3", kMidiTestPorts).rfind("no MIDI input port number 3 (ports: 0: 'Midi Through", 0), 0u);
  const std::string several = midi_select_error("midi 1", kMidiTestPorts);
  EXPECT_EQ(several.rfind("MIDI input 'midi 1' matches several ports ('nanoKONTROL2:nanoKONTROL2 MIDI 1 20:0', "
                          "'Launch Control XL:Launch Control XL MIDI 1 24:0'): give more of the name, or the port "
                          "number",
                          0),
            0u)
      << several;
  EXPECT_NE(midi_select_error("", kMidiTestPorts), "");  // "" is in every name: several
}

TEST(MidiInputAlsa, OpensAPortOrSaysWhatIsMissing) {
  avar::testing::RecordingControlSink sink;
  MidiInput input("Midi Through");
  EXPECT_EQ(input.describe(), "MIDI 'Midi Through'");
  if (const std::string missing = midi_input_missing(); !missing.empty()) {
    try {
      input.start(sink);
      ADD_FAILURE() << "started without an ALSA sequencer";
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()), "MIDI input 'Midi Through': " + missing);
    }
    input.stop();
    GTEST_SKIP() << missing;
  }
  // The sequencer is there; its "Midi Through" client (snd-seq-dummy) echoes what it is sent.
  RtMidiOut out(RtMidi::LINUX_ALSA, "avar test");
  unsigned through = out.getPortCount();
  for (unsigned i = 0; i < out.getPortCount(); ++i)
    if (out.getPortName(i).find("Midi Through") != std::string::npos) through = i;
  if (through == out.getPortCount()) GTEST_SKIP() << "no ALSA 'Midi Through' port to send to (sudo modprobe snd-seq-dummy)";
  input.start(sink);
  EXPECT_NE(input.describe().find("Midi Through"), std::string::npos) << input.describe();
  out.openPort(through);
  const std::vector<std::vector<unsigned char>> messages{
      {0xB0, 0x07, 0x7F}, {0xF8} /* clock: filtered before the decoder */, {0xC0, 0x05}, {0xE1, 0x00, 0x40}};
  for (const auto& m : messages) out.sendMessage(&m);
  ASSERT_TRUE(avar::testing::eventually([&] { return input.counters().messages >= 3; }));
  input.stop();
  input.stop();
  const auto posts = sink.posts();
  ASSERT_EQ(posts.size(), 2u);
  EXPECT_EQ(posts[0].name, "ch1.cc7");
  EXPECT_EQ(posts[0].value, 1.0);
  EXPECT_EQ(posts[1].name, "ch2.bend");
  EXPECT_EQ(posts[1].value, 0.0);
  EXPECT_TRUE(posts[1].bipolar);
  EXPECT_EQ(input.counters().ignored, 1u);
}

}  // namespace
}  // namespace avar::inputs
