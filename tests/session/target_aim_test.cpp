// A target held by hand: an aim command puts one of the show's inverse-kinematics targets at a
// point, the neck turns to look there within its limits, and letting go hands the target back
// to the show's path. On the gaze head with look-around (its eyes follow a fly), stepped.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <vector>

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

}  // namespace
}  // namespace avar::session
