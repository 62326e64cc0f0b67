#include "avar/playback/sampler.hpp"

#include <gtest/gtest.h>

namespace avar::playback {
namespace {

Track track(const std::string& channel, std::vector<std::pair<double, double>> keys) {
  RawCurve raw;
  for (auto [t, v] : keys) {
    RawKey k;
    k.time = t;
    k.value = v;
    raw.keys.push_back(k);
  }
  Curve curve = Curve::build(raw);
  return Track{channel, raw, std::move(curve), {}};
}

TEST(Sampler, WritesEveryChannelWithDefaultsForUndrivenOnes) {
  Show show;
  show.duration = 2;
  show.tracks.push_back(track("b", {{0, 0}, {2, 20}}));
  Sampler sampler(show, {1}, {7, 0, 9});
  std::vector<double> frame(3, -1);
  sampler.sample(1.0, frame);
  EXPECT_EQ(frame, (std::vector<double>{7, 10, 9}));
}

TEST(Sampler, LoopingShowsWrapAtTheirDuration) {
  Show show;
  show.duration = 2;
  show.loop = true;
  show.tracks.push_back(track("a", {{0, 0}, {2, 20}}));
  Sampler sampler(show, {0}, {0});
  std::vector<double> frame(1);
  sampler.sample(2.5, frame);
  EXPECT_DOUBLE_EQ(frame[0], 5);
  sampler.sample(7.0, frame);
  EXPECT_DOUBLE_EQ(frame[0], 10);
  sampler.sample(0.5, frame);  // backwards after a wrap
  EXPECT_DOUBLE_EQ(frame[0], 5);
}

TEST(Sampler, RejectsBindingsOutsideTheFrame) {
  Show show;
  show.duration = 1;
  show.tracks.push_back(track("a", {{0, 0}}));
  EXPECT_THROW(Sampler(show, {3}, {0, 0}), std::invalid_argument);
  EXPECT_THROW(Sampler(show, {}, {0}), std::invalid_argument);
}

}  // namespace
}  // namespace avar::playback
