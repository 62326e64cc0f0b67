// The simulated Maestro decodes exactly the bytes the device accepts and answers with the exact
// reply bytes (shared/protocols/pololu-maestro.md), and moves its outputs by the guide's units.
#include "avar/sim/sim_maestro.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "avar/firmware_iface/maestro_codec.hpp"
#include "../support/encode.hpp"

namespace avar::sim {
namespace {

namespace maestro = firmware_iface::maestro;
using Bytes = std::vector<std::uint8_t>;
using Values = std::vector<std::uint16_t>;
using Form = MaestroCommand::Form;

SimMaestroConfig config(bool crc = false) {
  SimMaestroConfig c;
  c.crc = crc;
  c.log_limit = 1000;
  return c;
}

Bytes replies(SimMaestro& d) {
  std::array<std::uint8_t, 256> out{};
  const std::size_t n = d.take_replies(out);
  return Bytes(out.begin(), out.begin() + static_cast<long>(n));
}

/// Advances in 1 ms steps until channel ch reaches its target; returns the time taken.
double time_to_target(SimMaestro& d, int ch, double limit_s = 100) {
  int ms = 0;
  while (d.output_pulse(ch) != d.target(ch) && ms < limit_s * 1000) {
    d.advance(0.001);
    ++ms;
  }
  return ms / 1000.0;
}

// --- Decoding ---------------------------------------------------------------------------

TEST(SimMaestro, CompactSetTargetThenGetPosition) {
  SimMaestro d(config());
  d.receive(Bytes{0x84, 0x00, 0x70, 0x2E});  // M1: ch 0 = 6000
  EXPECT_EQ(d.target(0), 6000);
  d.receive(Bytes{0x84, 0x02, 0x70, 0x2E});  // M2: ch 2 = 6000
  EXPECT_EQ(d.target(2), 6000);
  d.receive(Bytes{0x90, 0x00});
  EXPECT_EQ(replies(d), (Bytes{0x70, 0x17}));  // M12
  ASSERT_EQ(d.log().size(), 3u);
  EXPECT_EQ(d.log()[0].command, maestro::kSetTarget);
  EXPECT_EQ(d.log()[0].channel, 0);
  EXPECT_EQ(d.log()[0].values, Values{6000});
  EXPECT_EQ(d.log()[0].form, Form::compact);
  EXPECT_EQ(d.log()[2].command, maestro::kGetPosition);
  EXPECT_EQ(d.bytes_received(), 10u);
  EXPECT_EQ(d.errors(), 0);
}

TEST(SimMaestro, PololuFormForThisDeviceActs) {
  SimMaestro d(config());
  d.receive(Bytes{0xAA, 0x0C, 0x04, 0x00, 0x70, 0x2E});  // M3, device 12
  EXPECT_EQ(d.target(0), 6000);
  EXPECT_EQ(d.log().back().form, Form::pololu);
  d.receive(Bytes{0xAA, 0x0C, 0x10, 0x00});
  EXPECT_EQ(replies(d), (Bytes{0x70, 0x17}));  // replies carry no framing
}

TEST(SimMaestro, PololuPacketsForAnotherDeviceAreSkippedWholly) {
  SimMaestroConfig c = config(true);
  SimMaestro d(c);
  d.receive(Bytes{0xAA, 0x05, 0x04, 0x01, 0x70, 0x2E, 0x00});  // device 5, CRC wrong for us too
  d.receive(Bytes{0xAA, 0x01, 0x10, 0x00, 0x6B});              // M7: device 1
  d.receive(Bytes{0xAA, 0x05, 0x55, 0x01});                    // a command we do not know
  d.receive(Bytes{0xAA, 0x05, 0x04});                          // cut short by the next packet
  d.receive(Bytes{0xAA, 0x0C, 0x04, 0x00, 0x70, 0x2E, 0x22});  // M9: ours
  EXPECT_EQ(d.target(0), 6000);
  EXPECT_EQ(d.target(1), 0);
  EXPECT_TRUE(replies(d).empty());
  EXPECT_EQ(d.errors(), 0);
  EXPECT_EQ(d.log().size(), 1u);
}

TEST(SimMaestro, SetMultipleTargetsAndTargetZeroStopsPulses) {
  SimMaestro d(config());
  d.receive(Bytes{0x84, 0x03, 0x70, 0x2E});
  EXPECT_EQ(d.output_pulse(3), 6000);
  d.receive(Bytes{0x9F, 0x02, 0x03, 0x00, 0x00, 0x70, 0x2E});  // M5: ch 3 off, ch 4 = 6000
  EXPECT_EQ(d.target(3), 0);
  EXPECT_EQ(d.output_pulse(3), 0);
  EXPECT_EQ(d.target(4), 6000);
  EXPECT_EQ(d.log().back().command, maestro::kSetMultipleTargets);
  EXPECT_EQ(d.log().back().channel, 3);
  EXPECT_EQ(d.log().back().values, (Values{0, 6000}));
  d.receive(Bytes{0x90, 0x03});
  EXPECT_EQ(replies(d), (Bytes{0x00, 0x00}));  // no pulses
  d.receive(Bytes{0xAA, 0x0C, 0x1F, 0x01, 0x17, 0x70, 0x2E});  // Pololu form, last channel
  EXPECT_EQ(d.target(23), 6000);
  EXPECT_EQ(d.errors(), 0);
}

TEST(SimMaestro, SetMultipleTargetsBeyondTheChannelsIsAProtocolError) {
  for (const Bytes& bad : {Bytes{0x9F, 0x00, 0x00}, Bytes{0x9F, 0x19, 0x00}, Bytes{0x9F, 0x02, 0x17, 0x70, 0x2E, 0x70, 0x2E}}) {
    SimMaestro d(config());
    d.receive(bad);
    EXPECT_EQ(d.errors(), maestro::kSerialProtocolError);
    EXPECT_EQ(d.target(23), 0);
  }
}

TEST(SimMaestro, EveryCommandTheCodecEncodesIsDecodedAsSent) {
  const unsigned seed = std::random_device{}();
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> channel(0, 23);
  std::uniform_int_distribution<int> value(0, maestro::kMaxValue);
  std::uniform_int_distribution<int> kind(0, 7);
  for (int crc = 0; crc < 2; ++crc) {
    SimMaestroConfig c = config(crc == 1);
    c.device_number = 42;
    for (auto& ch : c.channels) {
      ch.min_us = 0.25;
      ch.max_us = maestro::kMaxValue / 4.0;
    }
    SimMaestro d(c);
    for (int i = 0; i < 3000; ++i) {
      const maestro::Framing f{(i & 1) != 0, 42, crc == 1};
      const auto ch = static_cast<std::uint8_t>(channel(rng));
      const auto v = static_cast<std::uint16_t>(value(rng));
      const int k = kind(rng);
      Bytes p;
      MaestroCommand expected{0, 0, {}, f.pololu ? Form::pololu : Form::compact};
      std::size_t reply_size = 0;
      switch (k) {
        case 0:
          p = testing::encode_into<maestro::kMaxPacketSize>([&](auto o) { return maestro::encode_set_target(o, f, ch, v); });
          expected = {maestro::kSetTarget, ch, {v}, expected.form};
          break;
        case 1: {
          const int count = std::uniform_int_distribution<int>(1, 24 - ch)(rng);
          Values targets(static_cast<std::size_t>(count));
          for (auto& t : targets) t = static_cast<std::uint16_t>(value(rng));
          p = testing::encode_into<maestro::kMaxPacketSize>([&](auto o) { return maestro::encode_set_multiple_targets(o, f, ch, targets); });
          expected = {maestro::kSetMultipleTargets, ch, targets, expected.form};
          break;
        }
        case 2:
          p = testing::encode_into<maestro::kMaxPacketSize>([&](auto o) { return maestro::encode_set_speed(o, f, ch, v); });
          expected = {maestro::kSetSpeed, ch, {v}, expected.form};
          break;
        case 3:
          p = testing::encode_into<maestro::kMaxPacketSize>([&](auto o) { return maestro::encode_set_acceleration(o, f, ch, v); });
          expected = {maestro::kSetAcceleration, ch, {std::min(v, maestro::kMaxAcceleration)}, expected.form};
          break;
        case 4:
          p = testing::encode_into<maestro::kMaxPacketSize>([&](auto o) { return maestro::encode_get_position(o, f, ch); });
          expected = {maestro::kGetPosition, ch, {}, expected.form};
          reply_size = 2;
          break;
        case 5:
          p = testing::encode_into<maestro::kMaxPacketSize>([&](auto o) { return maestro::encode_get_moving_state(o, f); });
          expected = {maestro::kGetMovingState, 0, {}, expected.form};
          reply_size = 1;
          break;
        case 6:
          p = testing::encode_into<maestro::kMaxPacketSize>([&](auto o) { return maestro::encode_get_errors(o, f); });
          expected = {maestro::kGetErrors, 0, {}, expected.form};
          reply_size = 2;
          break;
        default:
          p = testing::encode_into<maestro::kMaxPacketSize>([&](auto o) { return maestro::encode_go_home(o, f); });
          expected = {maestro::kGoHome, 0, {}, expected.form};
          break;
      }
      ASSERT_FALSE(p.empty());
      d.receive(p);
      ASSERT_EQ(d.errors(), 0) << "packet " << i;
      const MaestroCommand& got = d.log().back();
      ASSERT_EQ(got.command, expected.command) << "packet " << i;
      ASSERT_EQ(got.channel, expected.channel) << "packet " << i;
      ASSERT_EQ(got.values, expected.values) << "packet " << i;
      ASSERT_EQ(got.form, expected.form) << "packet " << i;
      ASSERT_EQ(replies(d).size(), reply_size) << "packet " << i;
      if (k == 0) {
        ASSERT_EQ(d.target(ch), v);
        ASSERT_TRUE(v == 0 || d.output_pulse(ch) != 0);
      }
    }
  }
}

TEST(SimMaestro, ByteAtATimeIsTheSameAsAllAtOnce) {
  Bytes stream;
  for (const Bytes& p : {Bytes{0x84, 0x00, 0x70, 0x2E}, Bytes{0xAA, 0x0C, 0x87, 0x01, 0x05, 0x00},
                         Bytes{0xFF, 0x02, 0xFE}, Bytes{0x9F, 0x02, 0x03, 0x20, 0x1F, 0x40, 0x3E}, Bytes{0x90, 0x04},
                         Bytes{0xA1}, Bytes{0x84, 0x05}, Bytes{0x93}, Bytes{0xA1}})
    stream.insert(stream.end(), p.begin(), p.end());
  SimMaestro whole(config());
  SimMaestro bytewise(config());
  whole.receive(stream);
  for (std::uint8_t b : stream) bytewise.receive(std::span(&b, 1));
  EXPECT_EQ(replies(whole), replies(bytewise));
  for (int ch = 0; ch < 24; ++ch) EXPECT_EQ(whole.target(ch), bytewise.target(ch));
  EXPECT_EQ(whole.log().size(), bytewise.log().size());
  EXPECT_EQ(whole.bytes_received(), stream.size());
  EXPECT_EQ(bytewise.bytes_received(), stream.size());
}

TEST(SimMaestro, MiniSscNeutralEndsAndOffset) {
  SimMaestroConfig c = config(true);  // Mini SSC never carries a CRC
  c.mini_ssc_offset = 10;
  c.channels[1].neutral_us = 1400;
  c.channels[1].range_us = 300;
  SimMaestro d(c);
  d.receive(Bytes{0xFF, 0x0A, 0x7F});  // M4 shifted by the offset: ch 0 to neutral
  EXPECT_EQ(d.target(0), 6000);
  d.receive(Bytes{0xFF, 0x0A, 0xFE});  // 254 = neutral + 476.25 µs = 1976.25 µs
  EXPECT_EQ(d.target(0), 7905);
  d.receive(Bytes{0xFF, 0x0A, 0x00});  // 0 = neutral - 476.25 µs = 1023.75 µs
  EXPECT_EQ(d.target(0), 4095);
  d.receive(Bytes{0xFF, 0x0B, 0xAA});  // data bytes may have the top bit set (0xAA is data here)
  EXPECT_EQ(d.target(1), maestro::quarter_us_from_us(1400 + (0xAA - 127.0) / 127.0 * 300));
  d.receive(Bytes{0xFF, 0x09, 0x7F, 0xFF, 0x22, 0x7F});  // addresses of other devices
  EXPECT_EQ(d.errors(), 0);
  ASSERT_EQ(d.log().size(), 4u);
  EXPECT_EQ(d.log().back().command, maestro::kMiniSscStart);
  EXPECT_EQ(d.log().back().channel, 1);
  EXPECT_EQ(d.log().back().values, Values{0xAA});
  EXPECT_EQ(d.log().back().form, Form::mini_ssc);
}

TEST(SimMaestro, TargetsAreClampedToTheChannelRange) {
  SimMaestro d(config());
  d.receive(Bytes{0x84, 0x00, 0x20, 0x1F});  // 1000 µs: inside 992..2000
  EXPECT_EQ(d.target(0), 4000);
  d.receive(Bytes{0x84, 0x00, 0x7F, 0x7F});  // 4095.75 µs: clamped to 2000 µs
  EXPECT_EQ(d.target(0), 8000);
  d.receive(Bytes{0x84, 0x00, 0x01, 0x00});  // 0.25 µs: clamped to 992 µs
  EXPECT_EQ(d.target(0), 3968);
  d.receive(Bytes{0x84, 0x00, 0x00, 0x00});  // 0 is "off", not a pulse width
  EXPECT_EQ(d.target(0), 0);
}

TEST(SimMaestro, ChannelsTheDeviceDoesNotHave) {
  SimMaestroConfig c = config();
  c.channel_count = 12;
  SimMaestro d(c);
  d.receive(Bytes{0x84, 0x0C, 0x70, 0x2E});  // channel 12 on a Mini 12: ignored
  d.receive(Bytes{0x90, 0x0C});
  EXPECT_EQ(replies(d), (Bytes{0x00, 0x00}));
  EXPECT_EQ(d.errors(), 0);
  d.receive(Bytes{0x9F, 0x02, 0x0B, 0x70, 0x2E, 0x70, 0x2E});  // would reach channel 12
  EXPECT_EQ(d.errors(), maestro::kSerialProtocolError);
  EXPECT_EQ(d.target(11), 0);
}

// --- CRC and errors ---------------------------------------------------------------------

TEST(SimMaestro, CrcIsCheckedAndABadOneIsAnError) {
  SimMaestro d(config(true));
  d.receive(Bytes{0x84, 0x00, 0x70, 0x2E, 0x2B});  // M8
  EXPECT_EQ(d.target(0), 6000);
  EXPECT_EQ(d.errors(), 0);
  d.receive(Bytes{0x84, 0x01, 0x70, 0x2E, 0x2B});  // wrong CRC for channel 1: ignored
  EXPECT_EQ(d.target(1), 0);
  EXPECT_EQ(d.errors(), maestro::kSerialCrcError);
  EXPECT_EQ(d.log().size(), 1u);
  d.receive(Bytes{0xA1, maestro::crc7(Bytes{0xA1})});
  EXPECT_EQ(replies(d), (Bytes{0x08, 0x00}));
}

TEST(SimMaestro, CrcCoversThePololuHeader) {
  SimMaestroConfig c = config(true);
  c.device_number = 1;
  SimMaestro d(c);
  d.receive(Bytes{0x84, 0x00, 0x70, 0x2E, 0x2B});
  d.receive(Bytes{0xAA, 0x01, 0x10, 0x00, 0x6B});  // M7
  EXPECT_EQ(replies(d), (Bytes{0x70, 0x17}));
  const std::uint8_t without_header = maestro::crc7(Bytes{0x10, 0x00});  // CRC over the command only
  ASSERT_NE(without_header, 0x6B);
  d.receive(Bytes{0xAA, 0x01, 0x10, 0x00, without_header});
  EXPECT_TRUE(replies(d).empty());
  EXPECT_EQ(d.errors(), maestro::kSerialCrcError);
}

TEST(SimMaestro, AMissingCrcByteLeavesThePacketUnfinished) {
  SimMaestro d(config(true));
  d.receive(Bytes{0x84, 0x00, 0x70, 0x2E});  // no CRC byte: still waiting
  EXPECT_EQ(d.target(0), 0);
  d.receive(Bytes{0xA1, maestro::crc7(Bytes{0xA1})});  // the next command interrupts it (and is itself fine)
  EXPECT_EQ(replies(d), (Bytes{0x10, 0x00}));
}

TEST(SimMaestro, GetErrorsRepliesAndClears) {
  SimMaestro d(config());
  d.receive(Bytes{0x84, 0x00});  // interrupted by the next command byte
  d.receive(Bytes{0x84, 0x00, 0x70, 0x2E});
  EXPECT_EQ(d.errors(), maestro::kSerialProtocolError);
  EXPECT_EQ(d.target(0), 6000);  // the interrupting packet itself counts
  d.receive(Bytes{0xA1});
  EXPECT_EQ(replies(d), (Bytes{0x10, 0x00}));
  EXPECT_EQ(d.errors(), 0);
  d.receive(Bytes{0xA1});
  EXPECT_EQ(replies(d), (Bytes{0x00, 0x00}));
}

TEST(SimMaestro, UnknownCommandsAreProtocolErrors) {
  for (const Bytes& bad : {Bytes{0xC5}, Bytes{0x80}, Bytes{0xAA, 0x0C, 0x45}, Bytes{0xAA, 0x0C, 0x2A}}) {
    SimMaestro d(config());
    d.receive(bad);
    EXPECT_EQ(d.errors(), maestro::kSerialProtocolError) << std::hex << int(bad.back());
  }
  SimMaestro d(config());
  d.receive(Bytes{0xAA, 0x84});  // the device number must be a data byte
  EXPECT_EQ(d.errors(), maestro::kSerialProtocolError);
}

TEST(SimMaestro, StrayDataBytesAreIgnored) {
  SimMaestro d(config());
  d.receive(Bytes{0x00, 0x70, 0x2E, 0x7F});
  EXPECT_EQ(d.errors(), 0);
  EXPECT_TRUE(d.log().empty());
}

TEST(SimMaestro, AnErrorSendsEveryChannelHome) {
  SimMaestroConfig c = config();
  c.channels[0].home_us = 1500;
  c.channels[2].home_ignore = true;
  SimMaestro d(c);
  d.receive(Bytes{0x84, 0x00, 0x20, 0x1F, 0x84, 0x01, 0x20, 0x1F, 0x84, 0x02, 0x20, 0x1F});
  d.receive(Bytes{0xC5});
  EXPECT_EQ(d.target(0), 6000);  // its home position
  EXPECT_EQ(d.target(1), 0);     // home "off": pulses stop
  EXPECT_EQ(d.output_pulse(1), 0);
  EXPECT_EQ(d.target(2), 4000);  // "ignore": unchanged
}

TEST(SimMaestro, GoHome) {
  SimMaestroConfig c = config();
  c.channels[0].home_us = 1200;
  c.channels[1].home_ignore = true;
  SimMaestro d(c);
  d.receive(Bytes{0x84, 0x00, 0x40, 0x3E, 0x84, 0x01, 0x40, 0x3E, 0x84, 0x02, 0x40, 0x3E});
  d.receive(Bytes{0xAA, 0x0C, 0x22});
  EXPECT_EQ(d.target(0), 4800);
  EXPECT_EQ(d.target(1), 8000);
  EXPECT_EQ(d.target(2), 0);
  EXPECT_EQ(d.errors(), 0);
}

TEST(SimMaestro, MicroMaestroHasNoSetMultipleTargetsNorSetPwm) {
  SimMaestroConfig c = config();
  c.channel_count = 6;
  SimMaestro d(c);
  d.receive(Bytes{0x9F, 0x01, 0x00, 0x70, 0x2E});
  EXPECT_EQ(d.target(0), 0);
  EXPECT_EQ(d.errors(), maestro::kSerialProtocolError);
  d.receive(Bytes{0xA1});
  replies(d);
  d.receive(Bytes{0x8A, 0x00, 0x01, 0x00, 0x02});
  EXPECT_EQ(d.errors(), maestro::kSerialProtocolError);
}

TEST(SimMaestro, ScriptAndPwmCommandsAreAcceptedOnAMiniMaestro) {
  SimMaestro d(config());
  d.receive(Bytes{0x8A, 0x10, 0x01, 0x20, 0x02});  // Set PWM: on 144, period 288 (1/48 µs)
  EXPECT_EQ(d.log().back().values, (Values{144, 288}));
  d.receive(Bytes{0xA4, 0xA7, 0x03, 0xA8, 0x03, 0x10, 0x00});
  EXPECT_EQ(d.log().back().command, maestro::kRestartScriptWithParameter);
  EXPECT_EQ(d.log().back().values, (Values{3, 16}));
  d.receive(Bytes{0xAE});
  EXPECT_EQ(replies(d), Bytes{0x01});  // no script running
  EXPECT_EQ(d.errors(), 0);
}

TEST(SimMaestro, LimitsAboveTheDevicesMaximaAreTruncated) {
  SimMaestro d(config());
  d.receive(Bytes{0x87, 0x00, 0x7F, 0x7F});  // speed 16383
  EXPECT_EQ(d.speed(0), 10000);
  d.receive(Bytes{0x89, 0x00, 0x7F, 0x7F});  // acceleration 16383
  EXPECT_EQ(d.acceleration(0), 255);
}

TEST(SimMaestro, RepliesQueueInOrderAndCanBeTakenInPieces) {
  SimMaestro d(config());
  d.receive(Bytes{0x84, 0x00, 0x70, 0x2E, 0x90, 0x00, 0x93, 0xA1, 0x90, 0x01});
  EXPECT_EQ(d.pending_replies(), 7u);
  std::array<std::uint8_t, 3> part{};
  EXPECT_EQ(d.take_replies(part), 3u);
  EXPECT_EQ(part, (std::array<std::uint8_t, 3>{0x70, 0x17, 0x00}));
  EXPECT_EQ(replies(d), (Bytes{0x00, 0x00, 0x00, 0x00}));
  EXPECT_EQ(d.pending_replies(), 0u);
}

TEST(SimMaestro, LogKeepsTheLatestCommands) {
  SimMaestroConfig c = config();
  c.log_limit = 2;
  SimMaestro d(c);
  d.receive(Bytes{0x84, 0x00, 0x70, 0x2E, 0x84, 0x01, 0x70, 0x2E, 0x84, 0x02, 0x70, 0x2E});
  ASSERT_EQ(d.log().size(), 2u);
  EXPECT_EQ(d.log()[0].channel, 1);
  EXPECT_EQ(d.log()[1].channel, 2);
  c.log_limit = 0;
  SimMaestro quiet(c);
  quiet.receive(Bytes{0x84, 0x00, 0x70, 0x2E});
  EXPECT_TRUE(quiet.log().empty());
}

TEST(SimMaestro, BaudDetection) {
  SimMaestroConfig c = config();
  c.baud_detect = true;
  {
    SimMaestro d(c);
    d.receive(Bytes{0x84, 0x00, 0x70, 0x2E});  // before detection: noise at an unknown rate
    EXPECT_EQ(d.target(0), 0);
    d.receive(Bytes{0xAA, 0x84, 0x00, 0x70, 0x2E});  // a lone 0xAA, then a compact packet
    EXPECT_EQ(d.target(0), 6000);
    EXPECT_EQ(d.errors(), 0);
    d.receive(Bytes{0xAA, 0x84, 0x01, 0x70, 0x2E});  // later, a lone 0xAA is an unfinished packet
    EXPECT_EQ(d.errors(), maestro::kSerialProtocolError);
  }
  {
    SimMaestro d(c);
    d.receive(Bytes{0xAA, 0x0C, 0x04, 0x00, 0x70, 0x2E});  // the 0xAA also begins a Pololu packet
    EXPECT_EQ(d.target(0), 6000);
    EXPECT_EQ(d.errors(), 0);
  }
  {
    SimMaestro d(c);
    d.receive(Bytes{0xAA, 0xAA, 0x0C, 0x21});  // lone 0xAA, then Pololu Get Errors
    EXPECT_EQ(replies(d), (Bytes{0x00, 0x00}));
  }
}

TEST(SimMaestro, ConfigurationIsChecked) {
  const auto rejects = [](auto change) {
    SimMaestroConfig c;
    change(c);
    EXPECT_THROW(SimMaestro{c}, std::invalid_argument);
  };
  rejects([](SimMaestroConfig& c) { c.channel_count = 8; });
  rejects([](SimMaestroConfig& c) { c.device_number = 128; });
  rejects([](SimMaestroConfig& c) { c.mini_ssc_offset = 255; });
  rejects([](SimMaestroConfig& c) { c.channels[3].min_us = 2100; });
  rejects([](SimMaestroConfig& c) { c.channels[3].max_us = 5000; });
  rejects([](SimMaestroConfig& c) { c.channels[3].home_us = 500; });
  rejects([](SimMaestroConfig& c) { c.servo.max_speed_us_per_s = 0; });
  rejects([](SimMaestroConfig& c) { c.servo.deadband_us = -1; });
  SimMaestroConfig micro;
  micro.channel_count = 6;
  micro.channels[10].min_us = 5000;  // a channel the device does not have
  EXPECT_NO_THROW(SimMaestro{micro});
}

// --- Motion -----------------------------------------------------------------------------

TEST(SimMaestro, FirstPulseAfterNoneIsImmediate) {
  SimMaestro d(config());
  d.receive(Bytes{0x87, 0x00, 0x01, 0x00, 0x89, 0x00, 0x01, 0x00});  // slowest limits
  d.receive(Bytes{0x84, 0x00, 0x70, 0x2E});
  EXPECT_EQ(d.output_pulse(0), 6000);  // the device does not know where the servo is
  d.receive(Bytes{0x93});
  EXPECT_EQ(replies(d), Bytes{0x00});
}

TEST(SimMaestro, NoLimitsMeansTheOutputJumps) {
  SimMaestro d(config());
  d.receive(Bytes{0x84, 0x00, 0x20, 0x1F, 0x84, 0x00, 0x40, 0x3E});
  EXPECT_EQ(d.output_pulse(0), 4000);  // targets take effect on the next update
  d.advance(0.0001);
  EXPECT_EQ(d.output_pulse(0), 8000);
}

TEST(SimMaestro, SpeedLimitMatchesTheGuidesWorkedExample) {
  // Speed 140 = 3.5 µs/ms: 1000 -> 1350 µs takes 100 ms.
  SimMaestro d(config());
  d.receive(Bytes{0x84, 0x05, 0x20, 0x1F});  // 1000 µs (first pulse: immediate)
  d.receive(Bytes{0x87, 0x05, 0x0C, 0x01});  // M6: speed 140
  EXPECT_EQ(d.speed(5), 140);
  d.receive(testing::encode_into<maestro::kMaxPacketSize>([](auto o) { return maestro::encode_set_target(o, {}, 5, 5400); }));
  for (int i = 0; i < 99; ++i) d.advance(0.001);
  EXPECT_NEAR(d.output_pulse(5), 4000 + 14 * 99, 1e-6);
  d.receive(Bytes{0x90, 0x05});
  EXPECT_EQ(replies(d), (Bytes{0x0A, 0x15}));  // 5386 quarter-µs, still on its way
  d.receive(Bytes{0x93});
  EXPECT_EQ(replies(d), Bytes{0x01});
  d.advance(0.001);
  EXPECT_DOUBLE_EQ(d.output_pulse(5), 5400);
  d.receive(Bytes{0x93});
  EXPECT_EQ(replies(d), Bytes{0x00});
}

TEST(SimMaestro, SlowestSpeedTakesFortySecondsForOneMillisecond) {
  // Speed 1: 1 ms -> 2 ms takes 40 s; speed 4 = 100 µs/s.
  SimMaestro d(config());
  d.receive(Bytes{0x84, 0x00, 0x20, 0x1F, 0x87, 0x00, 0x01, 0x00, 0x84, 0x00, 0x40, 0x3E});
  d.advance(39.99);
  EXPECT_LT(d.output_pulse(0), 8000);
  d.advance(0.01);
  EXPECT_EQ(d.output_pulse(0), 8000);
  d.receive(Bytes{0x87, 0x00, 0x04, 0x00, 0x84, 0x00, 0x20, 0x1F});
  d.advance(1.0);
  EXPECT_NEAR(d.output_pulse(0), 8000 - 400, 1e-6);  // 100 µs in 1 s
}

TEST(SimMaestro, AccelerationRampsSpeedUpAndDown) {
  SimMaestro d(config());
  d.receive(Bytes{0x84, 0x00, 0x20, 0x1F});  // 1000 µs
  d.receive(Bytes{0x89, 0x00, 0x04, 0x00});  // acceleration 4 = 1250 µs/s²
  d.receive(Bytes{0x84, 0x00, 0x40, 0x3E});  // to 2000 µs
  d.receive(Bytes{0x93});
  EXPECT_EQ(replies(d), Bytes{0x01});  // moving
  // Without a speed limit a 1000 µs move at 1250 µs/s² takes 2 sqrt(1000 / 1250) = 1.789 s,
  // half of it speeding up: 500 µs in the first 0.894 s.
  d.advance(std::sqrt(1000.0 / 1250.0));
  EXPECT_NEAR(d.output_pulse(0), 6000, 1e-6);
  d.advance(std::sqrt(1000.0 / 1250.0) - 0.001);
  EXPECT_LT(d.output_pulse(0), 8000);
  EXPECT_NEAR(d.output_pulse(0), 8000 - 4 * 0.5 * 1250 * 0.001 * 0.001, 1e-6);  // braking: ½ a t² left
  d.advance(0.001);
  EXPECT_EQ(d.output_pulse(0), 8000);
  d.receive(Bytes{0x93});
  EXPECT_EQ(replies(d), Bytes{0x00});
}

TEST(SimMaestro, SlowestAccelerationFromTheGuide) {
  // Acceleration 1 = 312.5 µs/s²: 1 ms -> 2 ms takes 2 sqrt(1000 / 312.5) = 3.58 s (the guide
  // rounds this to "about 3 s").
  SimMaestro d(config());
  d.receive(Bytes{0x84, 0x00, 0x20, 0x1F, 0x89, 0x00, 0x01, 0x00, 0x84, 0x00, 0x40, 0x3E});
  EXPECT_NEAR(time_to_target(d, 0), 2 * std::sqrt(1000 / 312.5), 0.0011);
}

TEST(SimMaestro, SpeedAndAccelerationMakeATrapezoid) {
  // 1000 µs at 2500 µs/s (speed 100) and 12500 µs/s² (acceleration 40): 0.2 s up to speed
  // (250 µs), 0.2 s cruise (500 µs), 0.2 s down (250 µs) = 0.6 s.
  SimMaestro d(config());
  d.receive(Bytes{0x84, 0x00, 0x20, 0x1F, 0x87, 0x00, 0x64, 0x00, 0x89, 0x00, 0x28, 0x00, 0x84, 0x00, 0x40, 0x3E});
  d.advance(0.2);
  EXPECT_NEAR(d.output_pulse(0), 4000 + 4 * 250, 1e-6);
  d.advance(0.2);
  EXPECT_NEAR(d.output_pulse(0), 4000 + 4 * 750, 1e-6);
  d.advance(0.1999);
  EXPECT_LT(d.output_pulse(0), 8000);
  d.advance(0.0001);
  EXPECT_EQ(d.output_pulse(0), 8000);
}

TEST(SimMaestro, MotionDoesNotDependOnTheStepSizeAndKeepsItsSpeedLimit) {
  const unsigned seed = std::random_device{}();
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> target(3968, 8000);
  std::uniform_int_distribution<int> speed(0, 200);
  std::uniform_int_distribution<int> accel(0, 60);
  std::uniform_real_distribution<double> step(0.0002, 0.05);
  for (int trial = 0; trial < 100; ++trial) {
    SimMaestro fine(config());
    SimMaestro coarse(config());
    const auto s = static_cast<std::uint16_t>(speed(rng));
    const auto a = static_cast<std::uint16_t>(accel(rng));
    std::array<std::uint8_t, maestro::kMaxPacketSize> buf{};
    const auto send = [&](std::size_t n) {
      fine.receive(std::span(buf.data(), n));
      coarse.receive(std::span(buf.data(), n));
    };
    send(maestro::encode_set_target(buf, {}, 0, static_cast<std::uint16_t>(target(rng))));
    send(maestro::encode_set_speed(buf, {}, 0, s));
    send(maestro::encode_set_acceleration(buf, {}, 0, a));
    const double v_max = s ? s * 100.0 : 1e18;  // quarter-µs/s
    // Targets change in mid-motion: the same spans of time, split into random steps for one
    // device and 1 ms steps for the other, end at the same output.
    for (int leg = 0; leg < 4; ++leg) {
      send(maestro::encode_set_target(buf, {}, 0, static_cast<std::uint16_t>(target(rng))));
      double span = 0;
      for (int k = 0; k < 20; ++k) {
        const double h = step(rng);
        coarse.advance(h);
        span += h;
      }
      const int ms = static_cast<int>(std::floor(span * 1000));
      for (int k = 0; k < ms; ++k) {
        const double before = fine.output_pulse(0);
        fine.advance(0.001);
        ASSERT_LE(std::abs(fine.output_pulse(0) - before), v_max * 0.001 * (1 + 1e-9)) << "trial " << trial;
        ASSERT_GE(fine.output_pulse(0), 3968 - 1e-9);
        ASSERT_LE(fine.output_pulse(0), 8000 + 1e-9);
      }
      fine.advance(span - ms * 0.001);
      ASSERT_NEAR(fine.output_pulse(0), coarse.output_pulse(0), 1e-6) << "trial " << trial << " leg " << leg;
    }
  }
}

TEST(SimMaestro, AccelerationLimitHoldsOnEveryMoveFromRest) {
  const unsigned seed = std::random_device{}();
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> target(3968, 8000);
  std::uniform_int_distribution<int> speed(0, 200);
  std::uniform_int_distribution<int> accel(1, 60);
  for (int trial = 0; trial < 50; ++trial) {
    SimMaestro d(config());
    const auto s = static_cast<std::uint16_t>(speed(rng));
    const auto a = static_cast<std::uint16_t>(accel(rng));
    std::array<std::uint8_t, maestro::kMaxPacketSize> buf{};
    const auto send = [&](std::size_t n) { d.receive(std::span(buf.data(), n)); };
    send(maestro::encode_set_target(buf, {}, 0, static_cast<std::uint16_t>(target(rng))));
    send(maestro::encode_set_speed(buf, {}, 0, s));
    send(maestro::encode_set_acceleration(buf, {}, 0, a));
    const double v_max = s ? s * 100.0 : 1e18;
    const double a_max = a * 1250.0;
    for (int leg = 0; leg < 3; ++leg) {
      const auto goal = static_cast<std::uint16_t>(target(rng));
      send(maestro::encode_set_target(buf, {}, 0, goal));
      const double distance = std::abs(goal - d.output_pulse(0));
      // Mean velocities over 1 ms windows: each within the speed limit, and adjacent ones
      // (starting from rest) differing by at most a * 1 ms.
      double previous = 0;
      int ms = 0;
      while (d.output_pulse(0) != goal) {
        const double before = d.output_pulse(0);
        d.advance(0.001);
        ++ms;
        const double velocity = (d.output_pulse(0) - before) / 0.001;
        ASSERT_LE(std::abs(velocity), v_max * (1 + 1e-9)) << "trial " << trial;
        ASSERT_LE(std::abs(velocity - previous), a_max * 0.001 * (1 + 1e-9) + 1e-6) << "trial " << trial << " ms " << ms;
        previous = velocity;
        ASSERT_LT(ms, 100000) << "trial " << trial;
      }
      ASSERT_LE(std::abs(previous), a_max * 0.001 * (1 + 1e-9) + 1e-6);  // it arrives at rest
      // The time is that of the trapezoid (or triangle) profile, to the 1 ms step.
      const double ramp = std::min(v_max / a_max, std::sqrt(distance / a_max));
      const double expected = 2 * ramp + (distance - a_max * ramp * ramp) / std::min(v_max, a_max * ramp + 1e-300);
      ASSERT_NEAR(ms / 1000.0, expected, 0.0011) << "trial " << trial;
    }
  }
}

TEST(SimMaestro, ServoFollowsTheOutputWithLag) {
  SimMaestroConfig c = config();
  c.channels[0].initial_position_us = 1500;
  SimMaestro d(c);
  d.receive(Bytes{0x84, 0x00, 0x40, 0x3E});  // 2000 µs
  d.advance(0.01);
  EXPECT_GT(d.servo_position_us(0), 1500);
  EXPECT_LT(d.servo_position_us(0), 2000);
  for (int i = 0; i < 100; ++i) d.advance(0.01);
  EXPECT_NEAR(d.servo_position_us(0), 2000, c.servo.deadband_us);
}

TEST(SimMaestro, ServoStaysWhereItIsWithoutPulses) {
  SimMaestroConfig c = config();
  c.channels[1].initial_position_us = 1234;
  SimMaestro d(c);
  d.advance(1.0);
  EXPECT_DOUBLE_EQ(d.servo_position_us(1), 1234);
  d.receive(Bytes{0x84, 0x01, 0x40, 0x3E, 0x84, 0x01, 0x00, 0x00});  // on, then off again
  d.advance(1.0);
  EXPECT_DOUBLE_EQ(d.servo_position_us(1), 1234);
}

}  // namespace
}  // namespace avar::sim
