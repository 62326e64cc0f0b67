#include "avar/core/timecode.hpp"

#include <gtest/gtest.h>

#include <random>

namespace avar {
namespace {

Timecode tc(int h, int m, int s, int f, FrameRate r) { return Timecode{h, m, s, f, r}; }

TEST(TimecodeMaths, NonDropFrameNumbersAreLabelsTimesRate) {
  EXPECT_EQ(to_frame_number(tc(0, 0, 1, 0, FrameRate::fps25)), 25);
  EXPECT_EQ(to_frame_number(tc(1, 0, 0, 0, FrameRate::fps24)), 86400);
  EXPECT_EQ(to_frame_number(tc(0, 1, 0, 29, FrameRate::fps30)), 1829);
  EXPECT_EQ(from_frame_number(1829, FrameRate::fps30), tc(0, 1, 0, 29, FrameRate::fps30));
  EXPECT_DOUBLE_EQ(to_seconds(tc(0, 0, 2, 12, FrameRate::fps24)), 2.5);
}

TEST(TimecodeMaths, DropFrameSkipsTwoLabelsEachMinuteButTheTenth) {
  const FrameRate df = FrameRate::fps29_97df;
  // 00:00:59;29 is frame 1799; the next frame is labelled 00:01:00;02.
  EXPECT_EQ(to_frame_number(tc(0, 0, 59, 29, df)), 1799);
  EXPECT_EQ(from_frame_number(1800, df), tc(0, 1, 0, 2, df));
  EXPECT_EQ(to_frame_number(tc(0, 1, 0, 2, df)), 1800);
  // 00:09:59;29 is followed by 00:10:00;00 (minute 10 keeps its labels).
  const std::int64_t before_ten = to_frame_number(tc(0, 9, 59, 29, df));
  EXPECT_EQ(before_ten, 17981);
  EXPECT_EQ(from_frame_number(before_ten + 1, df), tc(0, 10, 0, 0, df));
  EXPECT_EQ(from_frame_number(17983, df), tc(0, 10, 0, 1, df));
  // One hour of drop-frame is 107892 frames: 3.6 s short of 108000 labels.
  EXPECT_EQ(to_frame_number(tc(1, 0, 0, 0, df)), 107892);
  EXPECT_NEAR(to_seconds(tc(1, 0, 0, 0, df)), 107892.0 * 1001.0 / 30000.0, 1e-9);
  EXPECT_FALSE(valid(tc(0, 1, 0, 0, df)));
  EXPECT_FALSE(valid(tc(0, 1, 0, 1, df)));
  EXPECT_TRUE(valid(tc(0, 10, 0, 0, df)));
  EXPECT_TRUE(valid(tc(0, 1, 0, 0, FrameRate::fps30)));
}

TEST(TimecodeMaths, FrameNumbersRoundTripEveryRate) {
  std::mt19937_64 rng(20261203);
  std::printf("seed 20261203\n");
  for (const FrameRate r : {FrameRate::fps24, FrameRate::fps25, FrameRate::fps29_97df, FrameRate::fps30}) {
    std::uniform_int_distribution<std::int64_t> pick(0, frames_per_day(r) - 1);
    for (int i = 0; i < 20000; ++i) {
      const std::int64_t n = pick(rng);
      const Timecode t = from_frame_number(n, r);
      ASSERT_TRUE(valid(t)) << to_string(t);
      ASSERT_EQ(to_frame_number(t), n) << to_string(t);
    }
    // Consecutive frames have consecutive, valid labels across a whole ten minutes.
    for (std::int64_t n = 0; n < 18000; ++n) ASSERT_EQ(to_frame_number(from_frame_number(n, r)), n);
    EXPECT_EQ(from_frame_number(-1, r), from_frame_number(frames_per_day(r) - 1, r));
  }
}

TEST(TimecodeMaths, ParsesAndPrintsLabels) {
  std::string why;
  const auto t = parse_timecode("01:02:03:04", FrameRate::fps25, &why);
  ASSERT_TRUE(t.has_value()) << why;
  EXPECT_EQ(*t, tc(1, 2, 3, 4, FrameRate::fps25));
  EXPECT_EQ(to_string(*t), "01:02:03:04");
  const auto d = parse_timecode("00:10:00;00", FrameRate::fps29_97df, &why);
  ASSERT_TRUE(d.has_value()) << why;
  EXPECT_EQ(to_string(*d), "00:10:00;00");
  EXPECT_FALSE(parse_timecode("00:01:00;00", FrameRate::fps29_97df, &why));
  EXPECT_NE(why.find("do not exist"), std::string::npos) << why;
  EXPECT_FALSE(parse_timecode("00:00:00:25", FrameRate::fps25, &why));
  EXPECT_NE(why.find("frames 0-24"), std::string::npos) << why;
  EXPECT_FALSE(parse_timecode("1:00:00:00", FrameRate::fps25, &why));
  EXPECT_FALSE(parse_timecode("01:00:00:00:00", FrameRate::fps25, &why));
  EXPECT_FALSE(parse_timecode("01-00:00:00", FrameRate::fps25, &why));
  EXPECT_FALSE(parse_timecode("", FrameRate::fps25, &why));
  EXPECT_EQ(parse_frame_rate("29.97df"), FrameRate::fps29_97df);
  EXPECT_EQ(parse_frame_rate("24"), FrameRate::fps24);
  EXPECT_FALSE(parse_frame_rate("23.976"));
}

}  // namespace
}  // namespace avar
