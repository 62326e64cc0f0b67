#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <vector>

#include "avar/inputs/artnet_timecode_codec.hpp"
#include "avar/inputs/ltc_audio.hpp"
#include "avar/inputs/ltc_decoder.hpp"
#include "avar/inputs/mtc_decoder.hpp"

namespace avar::inputs {
namespace {

using Bytes = std::vector<std::uint8_t>;

/// The eight quarter frames (F1 0nnn dddd) that name `t`, in sending order.
std::vector<Bytes> tcdec_quarter_frames(const Timecode& t, bool reverse = false) {
  const unsigned rate_bits = t.rate == FrameRate::fps24        ? 0
                             : t.rate == FrameRate::fps25      ? 1
                             : t.rate == FrameRate::fps29_97df ? 2
                                                               : 3;
  const std::array<unsigned, 8> nibbles{
      static_cast<unsigned>(t.frames) & 0xF,  static_cast<unsigned>(t.frames) >> 4,
      static_cast<unsigned>(t.seconds) & 0xF, static_cast<unsigned>(t.seconds) >> 4,
      static_cast<unsigned>(t.minutes) & 0xF, static_cast<unsigned>(t.minutes) >> 4,
      static_cast<unsigned>(t.hours) & 0xF,   (static_cast<unsigned>(t.hours) >> 4) | (rate_bits << 1)};
  std::vector<Bytes> out;
  for (unsigned i = 0; i < 8; ++i) {
    const unsigned piece = reverse ? 7 - i : i;
    out.push_back({0xF1, static_cast<std::uint8_t>((piece << 4) | nibbles[piece])});
  }
  return out;
}

TEST(TimecodeDecodersMtc, AssemblesEightQuarterFramesWithTheTwoFrameOffset) {
  MtcDecoder d;
  TimecodeFix fix;
  const Timecode t{1, 2, 3, 4, FrameRate::fps25};
  const auto pieces = tcdec_quarter_frames(t);
  for (std::size_t i = 0; i + 1 < pieces.size(); ++i) EXPECT_EQ(d.decode(pieces[i], fix), MtcVerdict::partial) << i;
  ASSERT_EQ(d.decode(pieces[7], fix), MtcVerdict::fix);
  // Named frame 01:02:03:04 when piece 0 went out; piece 7 arrives 1.75 frames later, and the
  // label shown is the "+2" frame.
  EXPECT_EQ(fix.label, (Timecode{1, 2, 3, 6, FrameRate::fps25}));
  EXPECT_DOUBLE_EQ(fix.frames_after, -0.25);
  EXPECT_NEAR(fix.seconds(), to_seconds(t) + 1.75 / 25.0, 1e-12);
  EXPECT_FALSE(fix.reverse);
  // The next sequence continues: every quarter frame is now a fix, a quarter frame apart.
  const auto next = tcdec_quarter_frames(Timecode{1, 2, 3, 6, FrameRate::fps25});
  for (std::size_t i = 0; i < 8; ++i) {
    ASSERT_EQ(d.decode(next[i], fix), MtcVerdict::fix) << i;
    EXPECT_NEAR(fix.seconds(), to_seconds(t) + (2.0 + static_cast<double>(i) / 4.0) / 25.0, 1e-12) << i;
  }
}

TEST(TimecodeDecodersMtc, ReadsEveryRateAndDropFrameAcrossTheMinute) {
  for (const FrameRate r : {FrameRate::fps24, FrameRate::fps25, FrameRate::fps29_97df, FrameRate::fps30}) {
    MtcDecoder d;
    TimecodeFix fix;
    const Timecode t = r == FrameRate::fps29_97df ? Timecode{0, 0, 59, 28, r} : Timecode{23, 59, 59, 0, r};
    MtcVerdict last = MtcVerdict::partial;
    for (const Bytes& m : tcdec_quarter_frames(t)) last = d.decode(m, fix);
    ASSERT_EQ(last, MtcVerdict::fix) << to_string(r);
    EXPECT_EQ(fix.label.rate, r);
    EXPECT_EQ(to_frame_number(fix.label), (to_frame_number(t) + 2) % frames_per_day(r)) << to_string(fix.label);
  }
  // 00:00:59;28 + 2 frames is 00:01:00;02 at 29.97 drop-frame.
  MtcDecoder d;
  TimecodeFix fix;
  for (const Bytes& m : tcdec_quarter_frames(Timecode{0, 0, 59, 28, FrameRate::fps29_97df})) (void)d.decode(m, fix);
  EXPECT_EQ(to_string(fix.label), "00:01:00;02");
}

TEST(TimecodeDecodersMtc, ReverseRunsCompleteOnPieceZero) {
  MtcDecoder d;
  TimecodeFix fix;
  const Timecode t{0, 0, 10, 10, FrameRate::fps30};
  const auto pieces = tcdec_quarter_frames(t, true);
  MtcVerdict last = MtcVerdict::partial;
  for (const Bytes& m : pieces) last = d.decode(m, fix);
  ASSERT_EQ(last, MtcVerdict::fix);
  EXPECT_TRUE(fix.reverse);
  EXPECT_EQ(fix.label, (Timecode{0, 0, 10, 8, FrameRate::fps30}));
  EXPECT_NEAR(fix.seconds(), to_seconds(t) - 1.75 / 30.0, 1e-12);
}

TEST(TimecodeDecodersMtc, FullFramesAndJunk) {
  MtcDecoder d;
  TimecodeFix fix;
  // F0 7F 7F 01 01 hr mn sc fr F7; hr = rate << 5 | hours (25 fps: 0x20).
  const Bytes full{0xF0, 0x7F, 0x7F, 0x01, 0x01, 0x21, 0x1E, 0x0F, 0x05, 0xF7};
  ASSERT_EQ(d.decode(full, fix), MtcVerdict::fix);
  EXPECT_EQ(fix.label, (Timecode{1, 30, 15, 5, FrameRate::fps25}));
  EXPECT_DOUBLE_EQ(fix.frames_after, 0.0);
  EXPECT_EQ(d.decode(Bytes{0x90, 60, 100}, fix), MtcVerdict::not_timecode);
  EXPECT_EQ(d.decode(Bytes{0xF0, 0x7E, 0x7F, 0x06, 0x01, 0xF7}, fix), MtcVerdict::not_timecode);
  EXPECT_EQ(d.decode(Bytes{}, fix), MtcVerdict::malformed);
  EXPECT_EQ(d.decode(Bytes{0xF1}, fix), MtcVerdict::malformed);
  EXPECT_EQ(d.decode(Bytes{0xF1, 0x80}, fix), MtcVerdict::malformed);
  EXPECT_EQ(d.decode(Bytes{0xF0, 0x7F, 0x7F, 0x01, 0x01, 0x21, 0x1E, 0x0F, 0x05}, fix), MtcVerdict::malformed);
  EXPECT_EQ(d.decode(Bytes{0xF0, 0x7F, 0x7F, 0x01, 0x01, 0x21, 0x3C, 0x0F, 0x05, 0xF7}, fix), MtcVerdict::malformed);
  EXPECT_EQ(d.decode(Bytes{0xF0, 0x7F, 0x7F, 0x01, 0x01, 0x21, 0x1E, 0x0F, 0x19, 0xF7}, fix), MtcVerdict::malformed);
  // A sequence that names frames 26 at 25 fps is malformed; a good one after it still locks.
  Timecode bad{0, 0, 0, 26, FrameRate::fps25};
  MtcVerdict last = MtcVerdict::partial;
  for (const Bytes& m : tcdec_quarter_frames(bad)) last = d.decode(m, fix);
  EXPECT_EQ(last, MtcVerdict::malformed);
  for (const Bytes& m : tcdec_quarter_frames(Timecode{0, 0, 1, 0, FrameRate::fps25})) last = d.decode(m, fix);
  EXPECT_EQ(last, MtcVerdict::fix);
}

TEST(TimecodeDecodersMtc, AJumpUnlocksUntilItsSequenceCompletes) {
  MtcDecoder d;
  TimecodeFix fix;
  for (const Bytes& m : tcdec_quarter_frames(Timecode{0, 0, 1, 0, FrameRate::fps25})) (void)d.decode(m, fix);
  const auto jumped = tcdec_quarter_frames(Timecode{0, 5, 0, 0, FrameRate::fps25});
  int fixes = 0;
  for (std::size_t i = 0; i < 8; ++i)
    if (d.decode(jumped[i], fix) == MtcVerdict::fix) ++fixes;
  // Piece 0 matched the predicted frame's nibble (frame 02 vs 00 differs: unlocked at once);
  // only the completing piece gives a fix, at the new place.
  EXPECT_EQ(fixes, 1);
  EXPECT_EQ(fix.label, (Timecode{0, 5, 0, 2, FrameRate::fps25}));
}

TEST(TimecodeDecodersArtnet, GoldenArtTimeCodePacket) {
  std::array<std::uint8_t, artnet::kTimeCodeSize> out{};
  ASSERT_EQ(artnet::encode_timecode(Timecode{10, 20, 30, 12, FrameRate::fps29_97df}, 3, out), artnet::kTimeCodeSize);
  // Art-Net 4: "Art-Net\0", OpCode 0x9700 little-endian, version 14, Filler1, StreamId, Frames,
  // Seconds, Minutes, Hours, Type (2: drop-frame).
  const std::array<std::uint8_t, 19> golden{'A', 'r', 't', '-', 'N', 'e', 't', 0, 0x00, 0x97, 0, 14, 0, 3, 12, 30, 20, 10, 2};
  EXPECT_EQ(out, golden);
  Timecode t;
  std::uint8_t stream = 0;
  ASSERT_EQ(artnet::decode_timecode(golden, t, &stream), artnet::TimeCodeVerdict::ok);
  EXPECT_EQ(t, (Timecode{10, 20, 30, 12, FrameRate::fps29_97df}));
  EXPECT_EQ(stream, 3);
  std::array<std::uint8_t, 10> small{};
  EXPECT_EQ(artnet::encode_timecode(t, 0, small), 0U);
}

TEST(TimecodeDecodersArtnet, BadPacketsOfEveryKind) {
  using V = artnet::TimeCodeVerdict;
  const Bytes good{'A', 'r', 't', '-', 'N', 'e', 't', 0, 0x00, 0x97, 0, 14, 0, 0, 1, 2, 3, 4, 1};
  Timecode t;
  const auto verdict = [&](Bytes b) { return artnet::decode_timecode(b, t); };
  EXPECT_EQ(verdict(good), V::ok);
  Bytes b = good;
  b[0] = 'X';
  EXPECT_EQ(verdict(b), V::not_artnet);
  EXPECT_EQ(verdict(Bytes(good.begin(), good.begin() + 9)), V::not_artnet);
  b = good;
  b[9] = 0x50;  // ArtDmx
  EXPECT_EQ(verdict(b), V::other_opcode);
  EXPECT_EQ(verdict(Bytes(good.begin(), good.begin() + 18)), V::too_short);
  b = good;
  b[11] = 13;
  EXPECT_EQ(verdict(b), V::old_version);
  b = good;
  b[18] = 4;
  EXPECT_EQ(verdict(b), V::bad_type);
  b = good;
  b[14] = 25;  // frame 25 at 25 fps
  EXPECT_EQ(verdict(b), V::out_of_range);
  b = good;
  b[18] = 2, b[14] = 0, b[15] = 0, b[16] = 1;  // 00:01:00;00 does not exist in drop-frame
  EXPECT_EQ(verdict(b), V::out_of_range);
  b = good;
  b.push_back(0);  // a longer packet from a later revision still reads
  EXPECT_EQ(verdict(b), V::ok);
}

TEST(TimecodeDecodersLtc, DecodesGeneratedAudioAtEveryRate) {
  for (const FrameRate r : {FrameRate::fps24, FrameRate::fps25, FrameRate::fps29_97df, FrameRate::fps30}) {
    const double sr = 48000;
    const Timecode start = r == FrameRate::fps29_97df ? Timecode{0, 0, 59, 20, r} : Timecode{1, 0, 0, 0, r};
    const std::vector<float> audio = encode_ltc_audio(start, 50, sr);
    LtcDecoder d(sr);
    std::vector<TimecodeFix> fixes;
    std::vector<std::int64_t> ends;
    // Fed in audio-device-sized blocks.
    for (std::size_t at = 0; at < audio.size(); at += 256) {
      const std::size_t n = std::min<std::size_t>(256, audio.size() - at);
      d.feed(std::span(audio.data() + at, n), [&](const TimecodeFix& f, std::int64_t end) {
        fixes.push_back(f);
        ends.push_back(end);
      });
    }
    ASSERT_GE(fixes.size(), 45U) << to_string(r);
    EXPECT_EQ(d.bad_frames(), 0U);
    const double spf = sr / frames_per_second(r);
    for (std::size_t i = 1; i < fixes.size(); ++i) {
      ASSERT_EQ(fixes[i].label.rate, r);
      EXPECT_EQ(to_frame_number(fixes[i].label), to_frame_number(fixes[i - 1].label) + 1) << to_string(fixes[i].label);
      // The position at the frame's end sample matches the sample clock within a few samples.
      const double frame = static_cast<double>(to_frame_number(fixes[i].label) - to_frame_number(start));
      EXPECT_NEAR(static_cast<double>(ends[i] + 1), (frame + fixes[i].frames_after) * spf, 3.0) << i;
    }
    if (r == FrameRate::fps29_97df) {
      bool crossed = false;
      for (const TimecodeFix& f : fixes) crossed = crossed || to_string(f.label) == "00:01:00;02";
      EXPECT_TRUE(crossed) << "the drop-frame minute boundary was not decoded";
    }
  }
}

// A fuzzer's find: 232 samples at 8 kHz that libltc reads as a reversed frame whose start it
// extrapolates to 4 samples before the audio began. End samples stay within the audio fed.
TEST(TimecodeDecodersLtc, EndSamplesStayWithinTheAudioFed) {
  const std::vector<std::int16_t> pcm{
      20859,  20859,  20859,  -21094, -21094, 20859,  20859,  -21094, -21094, -21094, 20859,  20859,  20859,  -21094, -21094,
      -21094, 10138,  -10201, 10200,  10023,  -10201, -10024, 10200,  10023,  -10201, -10024, 10200,  10087,  -10201, -10024,
      10200,  10023,  -10201, -10024, 10200,  10023,  -10201, -10024, 10200,  10023,  -10201, -9768,  10200,  10023,  -10201,
      10200,  -10201, 10200,  -10201, -10024, 10200,  10023,  -10201, -10024, 10200,  10023,  -10194, -10024, 10200,  10023,
      -10201, -10024, 10200,  10023,  -10201, -10024, 10200,  10023,  -10201, -10024, 10200,  10023,  -10201, -10024, 10200,
      10023,  -10201, -10024, 10200,  -10201, 10200,  10023,  -10201, -10024, 10200,  10023,  -10201, -10024, 10200,  10047,
      -10201, -10024, 10200,  10023,  -10201, -10024, 2264,   5749,   -28672, 97,     9984,   10027,  10023,  -10024, -10024,
      10023,  10023,  -10024, -10024, 10023,  10023,  -10024, -10024, 10023,  -10024, 10023,  10023,  -10024, -10024, 10023,
      8487,   -10024, -10024, 10023,  -10201, -10024, 10200,  10023,  -10201, -10024, 10200,  10023,  -10201, -10024, 10200,
      10023,  7463,   0,      9984,   10098,  -10201, -10024, 10200,  10023,  -10201, -10024, 10200,  -10201, 10200,  -10201,
      10200,  10023,  -10201, -10024, 10200,  10023,  -10201, -10024, 10200,  10023,  -10201, -10024, 10200,  26407,  -10201,
      -10024, 10200,  10023,  -10201, -10024, 10200,  10023,  -10201, -10024, 10200,  10023,  10030,  -10201, -10024, 10200,
      10023,  -10201, -10024, 10200,  10023,  -10201, -10024, 10200,  10023,  -10201, -10024, 10200,  -10024, -10201, -10024,
      10200,  -10201, 10200,  -10201, 10200,  -10201, 10200,  -10201, 10200,  -10201, 10200,  -10201, 10200,  -10201, 10200,
      -10201, 10200,  -10201, 10200,  -10201, 10200,  -10201, 10200,  -10201, 10200,  10023,  -26073, -25939, 31661,  31569,
      31569,  -26031, -25939, -25939, 16301,  31661,  -10159};
  std::vector<float> audio;
  for (const std::int16_t v : pcm) audio.push_back(static_cast<float>(v) / 32768.0F);
  LtcDecoder d(8000);
  std::uint64_t seen = 0;
  d.feed(audio, [&](const TimecodeFix&, std::int64_t end) {
    ++seen;
    EXPECT_GE(end, 0);
    EXPECT_LE(end, static_cast<std::int64_t>(audio.size()));
  });
  EXPECT_EQ(seen, d.frames());
  EXPECT_GE(seen, 1U) << "the input no longer decodes to a frame: the regression is not exercised";
}

TEST(TimecodeDecodersLtc, RejectsAbsurdSampleRates) { EXPECT_THROW(LtcDecoder(100.0), std::invalid_argument); }

}  // namespace
}  // namespace avar::inputs
