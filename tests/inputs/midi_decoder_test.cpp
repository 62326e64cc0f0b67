// MIDI 1.0 channel voice messages (Detailed Specification 4.2, "Summary of MIDI Messages") as
// named controls: golden bytes in, names and values out.
#include "avar/inputs/midi_decoder.hpp"

#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

namespace avar::inputs {
namespace {

struct MidiDecoded {
  std::string name;
  double value;
  bool bipolar;
};

std::optional<MidiDecoded> midi_decode(MidiDecoder& decoder, const std::vector<std::uint8_t>& bytes) {
  MidiControl c;
  c.value = -99;  // untouched when decode() says no
  if (!decoder.decode(bytes, &c)) {
    EXPECT_EQ(c.value, -99);
    return std::nullopt;
  }
  return MidiDecoded{std::string(c.name()), c.value, c.bipolar};
}

std::optional<MidiDecoded> midi_decode(const std::vector<std::uint8_t>& bytes) {
  MidiDecoder decoder;
  return midi_decode(decoder, bytes);
}

void expect_midi_control(const std::vector<std::uint8_t>& bytes, const std::string& name, double value, bool bipolar = false) {
  SCOPED_TRACE(name);
  const auto d = midi_decode(bytes);
  ASSERT_TRUE(d.has_value());
  EXPECT_EQ(d->name, name);
  EXPECT_DOUBLE_EQ(d->value, value);
  EXPECT_EQ(d->bipolar, bipolar);
}

TEST(MidiDecoder, NotesOnAndOff) {
  expect_midi_control({0x90, 0x3C, 0x40}, "ch1.note60", 64 / 127.0);  // middle C, velocity 64
  expect_midi_control({0x90, 0x3C, 0x7F}, "ch1.note60", 1.0);
  expect_midi_control({0x99, 0x24, 0x64}, "ch10.note36", 100 / 127.0);  // GM kick drum on channel 10
  expect_midi_control({0x80, 0x3C, 0x40}, "ch1.note60", 0.0);           // note-off: release velocity unused
  expect_midi_control({0x9F, 0x7F, 0x00}, "ch16.note127", 0.0);         // note-on velocity 0 is a note-off
  expect_midi_control({0x90, 0x00, 0x01}, "ch1.note0", 1 / 127.0);
}

TEST(MidiDecoder, ControlChangeIsSevenBitsUnipolar) {
  expect_midi_control({0xB0, 0x07, 0x7F}, "ch1.cc7", 1.0);  // channel volume, full
  expect_midi_control({0xB0, 0x07, 0x00}, "ch1.cc7", 0.0);
  expect_midi_control({0xBF, 0x01, 0x40}, "ch16.cc1", 64 / 127.0);  // modulation wheel
  expect_midi_control({0xB3, 0x27, 0x20}, "ch4.cc39", 32 / 127.0);  // an LSB is its own control by default
  expect_midi_control({0xB0, 0x77, 0x01}, "ch1.cc119", 1 / 127.0);
}

TEST(MidiDecoder, PitchBendIsFourteenBitsCentredAt8192) {
  expect_midi_control({0xE0, 0x00, 0x40}, "ch1.bend", 0.0, true);  // 0x2000 = 8192: centre
  expect_midi_control({0xE0, 0x00, 0x00}, "ch1.bend", -1.0, true);
  expect_midi_control({0xE0, 0x7F, 0x7F}, "ch1.bend", 1.0, true);  // 16383
  expect_midi_control({0xE5, 0x01, 0x40}, "ch6.bend", 1 / 8191.0, true);
  expect_midi_control({0xE5, 0x7F, 0x3F}, "ch6.bend", -1 / 8192.0, true);  // LSB first: 0x1FFF = 8191
  expect_midi_control({0xEF, 0x00, 0x20}, "ch16.bend", -0.5, true);        // 0x1000 = 4096
}

TEST(MidiDecoder, ChannelPressure) {
  expect_midi_control({0xD0, 0x40}, "ch1.pressure", 64 / 127.0);
  expect_midi_control({0xDF, 0x7F}, "ch16.pressure", 1.0);
}

TEST(MidiDecoder, IgnoresWhatIsNotAControl) {
  const std::vector<std::vector<std::uint8_t>> ignored{
      {0xA0, 0x3C, 0x40},                    // polyphonic key pressure
      {0xC0, 0x05},                          // program change
      {0xB0, 0x79, 0x00},                    // reset all controllers (channel mode)
      {0xB0, 0x7B, 0x00},                    // all notes off (channel mode)
      {0xBF, 0x78, 0x00},                    // all sound off (channel mode)
      {0xF0, 0x7E, 0x7F, 0x09, 0x01, 0xF7},  // system exclusive: General MIDI system on
      {0xF8},                                // timing clock
      {0xFA},                                // start
      {0xFC},                                // stop
      {0xFE},                                // active sensing
      {0xFF},                                // system reset
      {0xF2, 0x00, 0x08},                    // song position pointer
      {0xF1, 0x20},                          // MIDI time code quarter frame
      {},                                    // nothing
      {0x3C, 0x40},                          // running status (no status byte)
      {0x90, 0x3C},                          // too short
      {0x90, 0x3C, 0x40, 0x00},              // too long
      {0xD0},                                // too short
      {0x90, 0x3C, 0x80},                    // a data byte with the status bit set
      {0xB0, 0x87, 0x00},                    // likewise
  };
  for (const auto& bytes : ignored) EXPECT_FALSE(midi_decode(bytes).has_value()) << bytes.size() << " bytes";
}

TEST(MidiDecoder, FourteenBitControllersPairMsbAndLsb) {
  MidiDecoder decoder({.fourteen_bit_cc = true});
  // Channel volume 0x64 MSB then 0x20 LSB (spec: controller 39 is the LSB of controller 7).
  auto d = midi_decode(decoder, {0xB0, 0x07, 0x64});
  ASSERT_TRUE(d);
  EXPECT_EQ(d->name, "ch1.cc7");
  EXPECT_DOUBLE_EQ(d->value, (0x64 << 7) / 16383.0);  // a new MSB: the LSB counts as 0
  d = midi_decode(decoder, {0xB0, 0x27, 0x20});
  ASSERT_TRUE(d);
  EXPECT_EQ(d->name, "ch1.cc7");
  EXPECT_DOUBLE_EQ(d->value, ((0x64 << 7) | 0x20) / 16383.0);
  // A fine adjustment alone: the MSB is remembered.
  d = midi_decode(decoder, {0xB0, 0x27, 0x21});
  ASSERT_TRUE(d);
  EXPECT_DOUBLE_EQ(d->value, ((0x64 << 7) | 0x21) / 16383.0);
  // Per channel: channel 2's controller 7 has no MSB yet.
  d = midi_decode(decoder, {0xB1, 0x27, 0x7F});
  ASSERT_TRUE(d);
  EXPECT_EQ(d->name, "ch2.cc7");
  EXPECT_DOUBLE_EQ(d->value, 0x7F / 16383.0);
  // Full scale, and controllers past 63 still seven bits.
  midi_decode(decoder, {0xB0, 0x1F, 0x7F});
  d = midi_decode(decoder, {0xB0, 0x3F, 0x7F});
  ASSERT_TRUE(d);
  EXPECT_EQ(d->name, "ch1.cc31");
  EXPECT_DOUBLE_EQ(d->value, 1.0);
  d = midi_decode(decoder, {0xB0, 0x40, 0x7F});  // sustain pedal
  ASSERT_TRUE(d);
  EXPECT_EQ(d->name, "ch1.cc64");
  EXPECT_DOUBLE_EQ(d->value, 1.0);
}

TEST(MidiDecoder, EveryVoiceMessageNamesItsChannelOneToSixteen) {
  for (unsigned channel = 0; channel < 16; ++channel) {
    for (const unsigned kind : {0x80u, 0x90u, 0xB0u, 0xD0u, 0xE0u}) {
      std::vector<std::uint8_t> bytes{static_cast<std::uint8_t>(kind | channel), 0x10};  // cc16: not a mode message
      if (kind != 0xD0) bytes.push_back(0x7F);
      const auto d = midi_decode(bytes);
      ASSERT_TRUE(d);
      EXPECT_TRUE(d->name.starts_with("ch" + std::to_string(channel + 1) + ".")) << d->name;
      EXPECT_GE(d->value, d->bipolar ? -1.0 : 0.0);
      EXPECT_LE(d->value, 1.0);
    }
  }
}

}  // namespace
}  // namespace avar::inputs
