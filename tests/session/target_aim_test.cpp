// A target held by hand: an aim command puts one of the show's inverse-kinematics targets at a
// point, the neck turns to look there within its limits, and letting go hands the target back
// to the show's path; a live control (a stick) steers the target the same way, under the hand.
// On the gaze head with look-around (its eyes follow a fly), stepped.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <vector>

#include "avar/config/input_map.hpp"
#include "avar/control/live_inputs.hpp"
#include "session_fixture.hpp"

namespace avar::session {
namespace {

using test_support::example;
using test_support::Script;

std::atomic<int> never_interrupted{0};

struct AimRecord {
  std::size_t targets = 0;
  TargetRecord eyes;
  double pan = 0;  ///< neck_pan's command, deg
  CommandOutcome outcome = CommandOutcome::applied;
};

TEST(TargetAim, TheNeckLooksWhereTheTargetIsHeldAndFollowsTheShowWhenLetGo) {
  const rig::Rig rig = config::load_rig_file(example("rigs/gaze-head.yaml"));
  const playback::Show show = config::load_show_file(example("shows/look-around.yaml"));
  SessionConfig config = test_support::stepped_config();
  config.start_paused = true;  // the show's fly stays at its first point: (1, -0.8, 0.3), to the right
  ShowSession session(rig, show, config);
  std::vector<AimRecord> kept;
  Command aim{CommandKind::aim, 0, 0, {1.0, 0.6, 0.4}};  // held ahead, to the left, at eye height
  Script script([&](const TickRecord& r) {
    AimRecord a{r.target_count, r.targets[0], r.channels[*rig.find_channel("neck_pan")].command,
                r.command_count > 0 ? r.commands[0].outcome : CommandOutcome::applied};
    kept.push_back(a);
    bool queued = true;
    if (r.tick == 100) queued = session.command(aim);
    if (r.tick == 300) queued = session.command(Command{CommandKind::unaim, 0, 0, {}});
    if (r.tick == 500) queued = session.command(Command{CommandKind::aim, 1, 0, {1, 0, 0}});  // no second target
    if (r.tick == 510) session.stop();
    EXPECT_TRUE(queued) << r.tick;
  });
  session.add_observer(script);
  ASSERT_FALSE(session.start_links());
  session.begin();
  (void)session.run(never_interrupted);
  ASSERT_GT(kept.size(), 510u);
  // Following the show: the fly is to the right (negative y), so the neck pans right.
  EXPECT_EQ(kept[99].targets, 1u);
  EXPECT_FALSE(kept[99].eyes.held);
  EXPECT_NEAR(kept[99].eyes.point[1], -0.8, 1e-12);
  EXPECT_LT(kept[99].pan, -20);
  // Held at the point: the goal is the point, and 4 s later the neck looks left, toward it.
  EXPECT_EQ(kept[101].outcome, CommandOutcome::applied);
  EXPECT_TRUE(kept[299].eyes.held);
  EXPECT_EQ(kept[299].eyes.point, aim.point);
  EXPECT_GT(kept[299].pan, 20);
  // Never faster than the channel allows on the way (150 deg/s at 50 Hz: 3 deg a tick).
  for (std::size_t k = 101; k < 300; ++k) EXPECT_LE(std::abs(kept[k].pan - kept[k - 1].pan), 3.0 + 1e-9) << k;
  // Let go: the show's fly again.
  EXPECT_FALSE(kept[499].eyes.held);
  EXPECT_NEAR(kept[499].eyes.point[1], -0.8, 1e-12);
  EXPECT_LT(kept[499].pan, -20);
  // A target the show does not have is refused.
  EXPECT_EQ(kept[501].outcome, CommandOutcome::bad_target);
}

TEST(TargetAim, ALiveControlSteersTheTargetAndAHandOnTheTargetOutranksIt) {
  const rig::Rig rig = config::load_rig_file(example("rigs/gaze-head.yaml"));
  const playback::Show show = config::load_show_file(example("shows/look-around.yaml"));
  control::ControlMapping stick;  // a stick steering the gaze left and right, 1 m either way
  stick.control = "gaze_y";
  stick.output = control::MappingOutput::target;
  stick.effector = 0;  // eyes
  stick.axis = 1;
  stick.low = -1;
  stick.high = 1;
  stick.crossfade_s = 0.2;
  control::LiveInputs live(config::live_channels(rig), {stick}, config::live_effectors(rig));
  SessionConfig config = test_support::stepped_config();
  config.start_paused = true;  // the fly stays at (1, -0.8, 0.3), to the right
  config.live = &live;
  ShowSession session(rig, show, config);
  std::vector<AimRecord> kept;
  Script script([&](const TickRecord& r) {
    kept.push_back({r.target_count, r.targets[0], r.channels[*rig.find_channel("neck_pan")].command});
    if (r.tick == 100) live.sink().post("gaze_y", 0.6, true, 1);  // the stick pushed left
    bool queued = true;
    if (r.tick == 300) queued = session.command(Command{CommandKind::aim, 0, 0, {1.0, -0.5, 0.3}});
    if (r.tick == 400) queued = session.command(Command{CommandKind::unaim, 0, 0, {}});
    EXPECT_TRUE(queued) << r.tick;
    if (r.tick == 500) session.stop();
  });
  session.add_observer(script);
  ASSERT_FALSE(session.start_links());
  session.begin();
  (void)session.run(never_interrupted);
  ASSERT_GT(kept.size(), 500u);
  EXPECT_NEAR(kept[99].eyes.point[1], -0.8, 1e-12);
  EXPECT_LT(kept[99].pan, -20);
  // The stick's goal, x and z still the show's; the neck turned left toward it.
  EXPECT_NEAR(kept[299].eyes.point[1], 0.6, 1e-12);
  EXPECT_NEAR(kept[299].eyes.point[0], 1.0, 1e-12);
  EXPECT_NEAR(kept[299].eyes.point[2], 0.3, 1e-12);
  EXPECT_FALSE(kept[299].eyes.held);
  EXPECT_GT(kept[299].pan, 20);
  // The crossfade eases the goal over: its 1.4 m move spread over 0.2 s (10 ticks, smoothstep).
  for (std::size_t k = 102; k < 300; ++k) EXPECT_LT(std::abs(kept[k].eyes.point[1] - kept[k - 1].eyes.point[1]), 0.25) << k;
  // Never faster than the channel allows (150 deg/s at 50 Hz: 3 deg a tick).
  for (std::size_t k = 101; k < 500; ++k) EXPECT_LE(std::abs(kept[k].pan - kept[k - 1].pan), 3.0 + 1e-9) << k;
  // A hand on the target in the studio outranks the stick, and letting go gives it back.
  EXPECT_TRUE(kept[399].eyes.held);
  EXPECT_NEAR(kept[399].eyes.point[1], -0.5, 1e-12);
  EXPECT_LT(kept[399].pan, -15);
  EXPECT_NEAR(kept[499].eyes.point[1], 0.6, 1e-12);
  EXPECT_GT(kept[499].pan, 20);
}

}  // namespace
}  // namespace avar::session
