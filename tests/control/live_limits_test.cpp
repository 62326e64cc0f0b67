// Whatever live controls send (wild values, NaN, infinities, direct channel values far outside
// the limits, hand-overs at random), what leaves the tick stays inside every channel's limits and
// speed: the live layers pass the limiter like the show.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "../support/recording_link.hpp"
#include "avar/control/controller.hpp"
#include "avar/control/live_inputs.hpp"

namespace avar::control {
namespace {

rig::Rig live_limits_rig() {
  rig::Rig rig;
  rig.name = "live-limits";
  rig.channels.push_back({.name = "jaw",
                          .unit = "deg",
                          .min = 0,
                          .max = 30,
                          .rest = 0,
                          .max_velocity = 200,
                          .max_acceleration = 4000,
                          .max_jerk = 200000,
                          .ramp_velocity = 30,
                          .where = {}});
  rig.channels.push_back({.name = "pan",
                          .unit = "deg",
                          .min = -60,
                          .max = 60,
                          .rest = 0,
                          .max_velocity = 90,
                          .max_acceleration = 900,
                          .max_jerk = 20000,
                          .ramp_velocity = 30,
                          .where = {}});
  return rig;
}

TEST(LiveLimits, NoLiveControlMovesAChannelOutsideItsLimitsOrFasterThanAllowed) {
  const rig::Rig rig = live_limits_rig();
  playback::Show show;
  show.name = "hold";
  show.duration = 4;
  for (unsigned seed = 1; seed <= 40; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> wild(-1e6, 1e6), unit(-1.5, 1.5);
    ControlMapping jaw, pan, boost;
    jaw.control = "a";
    jaw.high = 30;
    jaw.crossfade_s = 0.05;
    jaw.timeout_s = 0.3;
    pan.control = "b";
    pan.channel = 1;
    pan.mode = MappingMode::relative;
    pan.rate = 500;
    boost.control = "c";
    boost.channel = 1;
    boost.high = 100;
    boost.priority = 20;
    boost.blend = Blend::additive;
    LiveInputs live({{"jaw", 0, 30}, {"pan", -60, 60}}, {jaw, pan, boost});
    testing::RecordingLink link;
    const double dt = 0.002;
    Controller controller(rig, show, {&link}, {.tick_period_s = dt, .live = &live});
    controller.begin(0, rig.rest_frame());
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    for (int k = 0; controller.active() && k < 5000; ++k) {
      switch (rng() % 8) {
        case 0: live.sink().post("a", unit(rng), false, k); break;
        case 1: live.sink().post("b", unit(rng), true, k); break;
        case 2: live.sink().post("c", unit(rng), false, k); break;
        case 3: live.sink().post("channel/jaw", wild(rng), false, k); break;
        case 4: live.sink().post("channel/pan", rng() % 2 ? nan : inf, false, k); break;
        case 5: live.sink().post("a", rng() % 2 ? -inf : nan, false, k); break;
        default: break;
      }
      controller.tick(k * dt);
    }
    ASSERT_EQ(controller.latched_fault().cause, FaultCause::none) << "seed " << seed;
    for (std::size_t f = 0; f < link.frames.size(); ++f)
      for (std::size_t c = 0; c < 2; ++c) {
        const rig::ChannelSpec& spec = rig.channels[c];
        ASSERT_GE(link.frames[f][c], spec.min) << "seed " << seed << " frame " << f;
        ASSERT_LE(link.frames[f][c], spec.max) << "seed " << seed << " frame " << f;
        if (f > 0) {
          ASSERT_LE(std::abs(link.frames[f][c] - link.frames[f - 1][c]), spec.max_velocity * dt * (1 + 1e-9) + 1e-12)
              << "seed " << seed << " frame " << f << " channel " << spec.name;
        }
      }
  }
}

}  // namespace
}  // namespace avar::control
