// An editor's session: a run that holds the show's end instead of ending, and a show replaced
// while it plays (the studio's edits), each seen in the records an observer gets.
#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <thread>

#include "session_fixture.hpp"

namespace avar::session {
namespace show_replace_test {

using test_support::example;
using test_support::KeepAll;
using test_support::Kept;
using test_support::Script;

using test_support::HelloHead;

SessionConfig editor_config() {
  SessionConfig config = test_support::stepped_config();
  config.hold_at_end = true;
  return config;
}

/// A 12 s show that holds the jaw at `value` and nothing else.
std::shared_ptr<const playback::Show> jaw_at(int value) {
  return std::make_shared<const playback::Show>(config::load_show_text(
      "name: edited\nduration: 12\nloop: false\ntracks:\n  jaw:\n    - {time: 0, value: " + std::to_string(value) + "}\n",
      "edited.yaml"));
}

std::atomic<int> not_interrupted{0};

TEST(EditorSession, HoldsTheEndOfTheShowPausedAndPlayStartsItOver) {
  HelloHead f;
  ShowSession session(f.rig, f.show, editor_config());
  KeepAll all;
  session.add_observer(all);
  Script script([&](const TickRecord& r) {
    if (r.tick == 900) session.play();  // 18 s: long past the 12 s show's end
    if (r.tick == 1000) session.stop();
  });
  session.add_observer(script);
  ASSERT_FALSE(session.start_links());
  session.begin();
  (void)session.run(not_interrupted);
  const std::vector<Kept> kept = all.kept();
  ASSERT_GT(kept.size(), 1001u);
  for (std::size_t k = 800; k <= 900; ++k) {
    EXPECT_EQ(kept[k].phase, control::Phase::running) << k;
    EXPECT_TRUE(kept[k].paused) << k;
    EXPECT_DOUBLE_EQ(kept[k].show_time_s, f.show.duration) << k;
  }
  // The held last frame is the show's own last frame.
  EXPECT_NEAR(kept[850].channels[f.channel("lid_left")].command, 30.0, 1e-9);
  EXPECT_FALSE(kept[901].paused);
  EXPECT_NEAR(kept[911].show_time_s, 0.2, 1e-9);
  EXPECT_EQ(kept[1001].phase, control::Phase::stopping);
  EXPECT_EQ(kept.back().phase, control::Phase::disabled);
  EXPECT_EQ(kept.back().fault, control::FaultCause::none);
}

TEST(EditorSession, AReplacedShowPlaysFromTheNextTickAndTheFigureGlidesToIt) {
  HelloHead f;
  const auto edited = jaw_at(20);
  const auto original = std::make_shared<const playback::Show>(f.show);
  SessionConfig config = editor_config();
  config.start_paused = true;
  ShowSession session(f.rig, f.show, config);
  KeepAll all;
  session.add_observer(all);
  std::vector<bool> handed(2, false);
  Script script([&](const TickRecord& r) {
    if (r.tick == 10) session.scrub(2.0);
    if (r.tick == 200) handed[0] = session.replace_show(edited);
    if (r.tick == 400) handed[1] = session.replace_show(original);
    if (r.tick == 600) session.stop();
  });
  session.add_observer(script);
  ASSERT_FALSE(session.start_links());
  session.begin();
  (void)session.run(not_interrupted);
  EXPECT_TRUE(handed[0]);
  EXPECT_TRUE(handed[1]);
  const std::vector<Kept> kept = all.kept();
  ASSERT_GT(kept.size(), 600u);
  const std::size_t jaw = f.channel("jaw");
  EXPECT_DOUBLE_EQ(kept[200].channels[jaw].target, 0.0);
  EXPECT_DOUBLE_EQ(kept[201].channels[jaw].target, 20.0);  // the next tick samples the edit
  EXPECT_LT(kept[201].channels[jaw].command, 20.0);        // and the figure glides there
  EXPECT_DOUBLE_EQ(kept[399].channels[jaw].command, 20.0);
  EXPECT_DOUBLE_EQ(kept[401].channels[jaw].target, 0.0);
  EXPECT_DOUBLE_EQ(kept[599].channels[jaw].command, 0.0);
  for (std::size_t k = 190; k < 600; ++k) EXPECT_DOUBLE_EQ(kept[k].show_time_s, 2.0) << k;
  // Never faster than the jaw may move.
  const double limit = f.rig.channels[jaw].max_velocity / config.rate_hz;
  EXPECT_LE(test_support::largest_step(kept, jaw), limit * (1 + 1e-9));
  EXPECT_EQ(kept.back().fault, control::FaultCause::none);
}

TEST(EditorSession, ReplacingAShowNeedsARunUnderWay) {
  HelloHead f;
  const auto edited = std::make_shared<const playback::Show>(f.show);
  ShowSession session(f.rig, f.show, editor_config());
  EXPECT_FALSE(session.replace_show(edited));
  ASSERT_FALSE(session.start_links());
  session.begin();
  EXPECT_FALSE(session.replace_show(edited, std::chrono::milliseconds(0)));
}

TEST(EditorSession, AShowThatDoesNotFitTheRigIsRefusedBeforeTheLoopSeesIt) {
  HelloHead f;
  const auto foreign = std::make_shared<const playback::Show>(config::load_show_text(
      "name: foreign\nduration: 1\nloop: false\ntracks:\n  flipper:\n    - {time: 0, value: 1}\n", "foreign.yaml"));
  ShowSession session(f.rig, f.show, editor_config());
  bool refused = false;
  Script script([&](const TickRecord& r) {
    if (r.tick != 5) return;
    try {
      (void)session.replace_show(foreign);
    } catch (const std::invalid_argument&) {
      refused = true;
    }
    session.stop();
  });
  session.add_observer(script);
  ASSERT_FALSE(session.start_links());
  session.begin();
  (void)session.run(not_interrupted);
  EXPECT_TRUE(refused);
}

TEST(EditorSession, ShowsReplacedFromAnotherThreadWhileTheLoopRunsInRealTime) {
  HelloHead f;
  const auto edited = jaw_at(20);
  const auto original = std::make_shared<const playback::Show>(f.show);
  SessionConfig config = editor_config();
  config.stepped = false;
  config.rate_hz = 200;
  config.realtime = {0, false, -1};
  ShowSession session(f.rig, f.show, config);
  KeepAll all;
  session.add_observer(all);
  std::atomic<bool> jaw_at_twenty{false};
  Script watch([&](const TickRecord& r) {
    if (r.channels[f.channel("jaw")].target == 20.0 && !jaw_at_twenty.exchange(true)) jaw_at_twenty.notify_all();
  });
  session.add_observer(watch);
  ASSERT_FALSE(session.start_links());
  session.begin();
  int handed = 0;
  std::thread editor([&] {
    // Wait for the run to be under way, then hand shows over as fast as the loop takes them.
    while (!session.replace_show(original, std::chrono::milliseconds(0))) std::this_thread::yield();
    for (int i = 0; i < 40; ++i) handed += session.replace_show(i % 2 ? original : edited) ? 1 : 0;
    EXPECT_TRUE(session.replace_show(edited));
    jaw_at_twenty.wait(false);  // an edited show has played
    session.stop();
  });
  (void)session.run(not_interrupted);
  editor.join();
  EXPECT_EQ(handed, 40);
  const std::vector<Kept> kept = all.kept();
  EXPECT_EQ(kept.back().fault, control::FaultCause::none);
  bool reached = false;
  for (const Kept& k : kept) reached = reached || k.channels[f.channel("jaw")].target == 20.0;
  EXPECT_TRUE(reached);
}

}  // namespace show_replace_test
}  // namespace avar::session
