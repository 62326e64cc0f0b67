// Keys as flat numbers (how they cross into the studio page's WebAssembly engine): every field
// survives the round trip, so the decoded keys build a curve with the same samples, bit for bit;
// a malformed array is refused naming the field.
#include "avar/playback/runtime/raw_curve_codec.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "avar/playback/runtime/curve.hpp"
#include "keys.hpp"

namespace avar::playback {
namespace {

using testing::key;
using testing::raw_curve;

RawCurve every_field() {
  RawKey a = key(0.5, 10, Interpolation::bezier, Handle{0.2, 8}, Handle{0.9, 14});
  a.left_type = HandleType::free;
  a.right_type = HandleType::aligned;
  RawKey b = key(1.5, -4, Interpolation::elastic);
  b.easing = Easing::ease_in_out;
  b.amplitude = 12;
  b.period = 0.25;
  b.back = 2.5;
  RawKey c = key(2.5, 7, Interpolation::kochanek_bartels);
  c.tension = 0.3, c.continuity = -0.2, c.bias = 0.6;
  c.in_slope = 4.5;
  RawKey d = key(3.0, 1, Interpolation::hermite);
  d.out_slope = -2;
  RawKey e = key(4.0, 3);
  e.in_slope = 1;
  RawCurve raw = raw_curve({a, b, c, d, e});
  raw.extrapolation = Extrapolation::linear;
  raw.auto_smoothing = AutoSmoothing::continuous_acceleration;
  raw.cycles = {CycleMode::mirror, CycleMode::repeat_offset, 2, 0};
  return raw;
}

TEST(RawCurveCodec, EveryFieldSurvivesAndTheCurveSamplesTheSame) {
  const RawCurve raw = every_field();
  const std::vector<double> flat = encode_raw_curve(raw);
  ASSERT_EQ(flat.size(), kRawCurveHeaderFields + raw.keys.size() * kRawCurveKeyFields);
  const RawCurve back = decode_raw_curve(flat);
  EXPECT_EQ(encode_raw_curve(back), flat);
  ASSERT_EQ(back.keys.size(), raw.keys.size());
  EXPECT_EQ(back.keys[0].left->time, 0.2);
  EXPECT_EQ(back.keys[0].right_type, HandleType::aligned);
  EXPECT_FALSE(back.keys[1].left.has_value());
  EXPECT_FALSE(back.keys[1].left_type.has_value());
  EXPECT_EQ(back.keys[2].in_slope, 4.5);
  EXPECT_FALSE(back.keys[2].out_slope.has_value());
  EXPECT_EQ(back.cycles.before, CycleMode::mirror);
  EXPECT_EQ(back.cycles.before_count, 2);
  const Curve original = Curve::build(raw), decoded = Curve::build(back);
  for (int i = -200; i <= 800; ++i) {
    const double t = i * 0.01;
    EXPECT_EQ(original.evaluate(t), decoded.evaluate(t)) << t;
  }
}

std::string refusal(std::vector<double> flat) {
  try {
    (void)decode_raw_curve(flat);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "taken";
}

TEST(RawCurveCodec, AMalformedArrayIsRefusedNamingTheField) {
  std::vector<double> flat = encode_raw_curve(every_field());
  EXPECT_EQ(refusal({}), "flat curve: ends before the format");
  std::vector<double> wrong_format = flat;
  wrong_format[0] = 2;
  EXPECT_EQ(refusal(wrong_format), "flat curve: not format 1");
  std::vector<double> short_keys(flat.begin(), flat.end() - 1);
  EXPECT_EQ(refusal(short_keys), "flat curve: 5 keys need 110 numbers after the header, found 109");
  std::vector<double> bad_interpolation = flat;
  bad_interpolation[kRawCurveHeaderFields + 2] = 99;
  EXPECT_EQ(refusal(bad_interpolation), "flat curve: a key's interpolation must be a whole number from 0 to 17");
  std::vector<double> half_enum = flat;
  half_enum[2] = 0.5;
  EXPECT_EQ(refusal(half_enum), "flat curve: the extrapolation must be a whole number from 0 to 1");
}

}  // namespace
}  // namespace avar::playback
