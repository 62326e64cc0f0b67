// The show session through the library alone, on a simulated figure: holds, seeks, scrubs,
// pause, stop and e-stop, each seen in the records an observer gets.
#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "session_fixture.hpp"

namespace avar::session {
namespace {

using test_support::example;
using test_support::KeepAll;
using test_support::Kept;

using Figure = test_support::HelloHead;
using test_support::stepped_config;

/// Calls `act` from the observer (on the stepped loop's thread, between ticks) at tick `at`.
template <typename F>
class AtTick final : public SessionObserver {
 public:
  AtTick(std::uint64_t at, F act) : at_(at), act_(std::move(act)) {}
  void on_tick(const TickRecord& r) override {
    if (r.tick == at_) act_(r);
  }

 private:
  std::uint64_t at_;
  F act_;
};

std::atomic<int> no_interrupts{0};

std::size_t first_running(const std::vector<Kept>& kept) {
  for (std::size_t k = 0; k < kept.size(); ++k)
    if (kept[k].phase == control::Phase::running) return k;
  return kept.size();
}

TEST(ShowSession, UncommandedRunPlaysTheShowToRestAndRecordsEveryTick) {
  Figure f;
  ShowSession session(f.rig, f.show, stepped_config());
  KeepAll all;
  session.add_observer(all);
  ASSERT_FALSE(session.start_links());
  session.begin();
  const control::RunResult run = session.run(no_interrupts);
  const std::vector<Kept> kept = all.kept();
  ASSERT_EQ(kept.size(), run.ticks);
  EXPECT_EQ(session.records_dropped(), 0u);
  for (std::size_t k = 0; k < kept.size(); ++k) EXPECT_EQ(kept[k].tick, k);
  EXPECT_EQ(kept.front().phase, control::Phase::homing);
  EXPECT_EQ(kept.back().phase, control::Phase::disabled);
  EXPECT_NEAR(session.controller().show_time(), f.show.duration, 0.05);
  // The simulator's ground truth came back as feedback; the records carry every link's counters.
  EXPECT_TRUE(std::isfinite(kept.back().channels[f.channel("jaw")].measured));
  ASSERT_EQ(kept.back().links.size(), f.rig.links.size());
  EXPECT_EQ(kept.back().links[0].exchanges, session.figure().counters(0).exchanges);
}

TEST(ShowSession, HoldIsClampedToTheRangeAndMovesWithinTheSpeedLimit) {
  Figure f;
  const std::size_t jaw = f.channel("jaw");
  const std::size_t pan = f.channel("neck_pan");
  ShowSession session(f.rig, f.show, stepped_config());
  KeepAll all;
  session.add_observer(all);
  // Half a second into the run: the jaw held far past its max, the neck far below its min.
  auto act = [&](const TickRecord&) {
    EXPECT_TRUE(session.hold(jaw, 1000));
    EXPECT_TRUE(session.hold(pan, -1e6));
  };
  AtTick<decltype(act)> at(40, act);
  session.add_observer(at);
  ASSERT_FALSE(session.start_links());
  session.begin();
  (void)session.run(no_interrupts);
  const std::vector<Kept> kept = all.kept();
  ASSERT_GT(kept.size(), 200u);
  ASSERT_EQ(kept[41].commands.size(), 2u);
  EXPECT_EQ(kept[41].commands[0].outcome, CommandOutcome::applied);
  EXPECT_TRUE(kept[41].channels[jaw].held);
  EXPECT_FALSE(kept[40].channels[jaw].held);
  const double dt = 1.0 / 50;
  for (std::size_t k = 42; k < kept.size() && kept[k].phase == control::Phase::running; ++k) {
    EXPECT_DOUBLE_EQ(kept[k].channels[jaw].target, f.rig.channels[jaw].max) << "tick " << k;
    EXPECT_DOUBLE_EQ(kept[k].channels[pan].target, f.rig.channels[pan].min) << "tick " << k;
  }
  for (const std::size_t c : {jaw, pan}) {
    EXPECT_LE(test_support::largest_step(kept, c), f.rig.channels[c].max_velocity * dt * (1 + 1e-9)) << f.rig.channels[c].name;
    for (const Kept& k : kept) {
      EXPECT_GE(k.channels[c].command, f.rig.channels[c].min);
      EXPECT_LE(k.channels[c].command, f.rig.channels[c].max);
    }
  }
  // The neck got there (it has two seconds and more at 180 °/s).
  const std::size_t last_running = [&] {
    std::size_t r = 0;
    for (std::size_t k = 0; k < kept.size(); ++k)
      if (kept[k].phase == control::Phase::running) r = k;
    return r;
  }();
  EXPECT_NEAR(kept[last_running].channels[pan].command, f.rig.channels[pan].min, 1e-6);
}

TEST(ShowSession, ReleaseGlidesBackToTheShow) {
  Figure f;
  const std::size_t pan = f.channel("neck_pan");
  ShowSession session(f.rig, f.show, stepped_config());
  KeepAll all;
  session.add_observer(all);
  auto hold = [&](const TickRecord&) { session.hold(pan, 60); };
  auto release = [&](const TickRecord&) { session.release(pan); };
  AtTick<decltype(hold)> at_hold(30, hold);
  AtTick<decltype(release)> at_release(200, release);
  session.add_observer(at_hold);
  session.add_observer(at_release);
  ASSERT_FALSE(session.start_links());
  session.begin();
  (void)session.run(no_interrupts);
  const std::vector<Kept> kept = all.kept();
  EXPECT_TRUE(kept[150].channels[pan].held);
  EXPECT_FALSE(kept[201].channels[pan].held);
  EXPECT_LE(test_support::largest_step(kept, pan), f.rig.channels[pan].max_velocity / 50 * (1 + 1e-9));
}

TEST(ShowSession, SeekGlidesWithinEveryChannelsSpeedLimit) {
  Figure f;
  ShowSession session(f.rig, f.show, stepped_config());
  KeepAll all;
  session.add_observer(all);
  auto seek = [&](const TickRecord&) { session.seek(9.0); };
  AtTick<decltype(seek)> at(100, seek);
  session.add_observer(at);
  ASSERT_FALSE(session.start_links());
  session.begin();
  (void)session.run(no_interrupts);
  const std::vector<Kept> kept = all.kept();
  ASSERT_EQ(kept[101].commands.size(), 1u);
  EXPECT_EQ(kept[101].commands[0].command.kind, CommandKind::seek);
  EXPECT_EQ(kept[101].commands[0].outcome, CommandOutcome::applied);
  // Show time jumped: 9 s at the seek's tick, then on at the loop's pace.
  EXPECT_DOUBLE_EQ(kept[101].show_time_s, 9.0);
  EXPECT_NEAR(kept[111].show_time_s, 9.2, 1e-9);
  for (std::size_t c = 0; c < f.rig.channels.size(); ++c)
    EXPECT_LE(test_support::largest_step(kept, c), f.rig.channels[c].max_velocity / 50 * (1 + 1e-9)) << f.rig.channels[c].name;
  // The show ended 3 s after the seek instead of 12 s in.
  EXPECT_LT(kept.size(), 101u + 50u * 3u + 200u);
}

TEST(ShowSession, ScrubPausesThereAndPlayResumes) {
  Figure f;
  ShowSession session(f.rig, f.show, stepped_config());
  KeepAll all;
  session.add_observer(all);
  auto scrub = [&](const TickRecord&) { session.scrub(5.0); };
  auto play = [&](const TickRecord&) { session.play(); };
  AtTick<decltype(scrub)> at_scrub(60, scrub);
  AtTick<decltype(play)> at_play(160, play);
  session.add_observer(at_scrub);
  session.add_observer(at_play);
  ASSERT_FALSE(session.start_links());
  session.begin();
  (void)session.run(no_interrupts);
  const std::vector<Kept> kept = all.kept();
  for (std::size_t k = 61; k <= 160; ++k) {
    EXPECT_TRUE(kept[k].paused);
    EXPECT_DOUBLE_EQ(kept[k].show_time_s, 5.0);
  }
  EXPECT_FALSE(kept[161].paused);
  EXPECT_NEAR(kept[171].show_time_s, 5.2, 1e-9);
}

TEST(ShowSession, StartsPausedUntilPlay) {
  Figure f;
  SessionConfig config = stepped_config();
  config.start_paused = true;
  ShowSession session(f.rig, f.show, config);
  KeepAll all;
  session.add_observer(all);
  auto play = [&](const TickRecord&) { session.play(); };
  AtTick<decltype(play)> at(100, play);
  session.add_observer(at);
  ASSERT_FALSE(session.start_links());
  session.begin();
  (void)session.run(no_interrupts);
  const std::vector<Kept> kept = all.kept();
  const std::size_t start = first_running(kept);
  ASSERT_LT(start, 100u);
  for (std::size_t k = start; k <= 100; ++k) EXPECT_DOUBLE_EQ(kept[k].show_time_s, 0.0);
  EXPECT_NEAR(kept[111].show_time_s, 0.2, 1e-9);
}

TEST(ShowSession, LoopOnStartsANonLoopingShowOverUntilStopped) {
  Figure f;
  ShowSession session(f.rig, f.show, stepped_config());
  KeepAll all;
  session.add_observer(all);
  auto loop = [&](const TickRecord&) { session.loop(true); };
  auto stop = [&](const TickRecord&) { session.stop(); };
  AtTick<decltype(loop)> at_loop(10, loop);
  AtTick<decltype(stop)> at_stop(1000, stop);  // 20 s: past the 12 s show's end
  session.add_observer(at_loop);
  session.add_observer(at_stop);
  ASSERT_FALSE(session.start_links());
  session.begin();
  (void)session.run(no_interrupts);
  const std::vector<Kept> kept = all.kept();
  ASSERT_GT(kept.size(), 1001u);
  EXPECT_EQ(kept[1000].phase, control::Phase::running);
  EXPECT_LT(kept[1000].show_time_s, f.show.duration);
  EXPECT_EQ(kept[1001].commands.at(0).command.kind, CommandKind::stop);
  EXPECT_EQ(kept[1001].phase, control::Phase::stopping);
  EXPECT_EQ(kept.back().phase, control::Phase::disabled);
  EXPECT_EQ(kept.back().fault, control::FaultCause::none);
}

TEST(ShowSession, CommandsAfterTheShowAreRefusedAndBadOnesNamed) {
  Figure f;
  ShowSession session(f.rig, f.show, stepped_config());
  KeepAll all;
  session.add_observer(all);
  auto bad = [&](const TickRecord&) {
    session.hold(99, 1);
    session.hold(0, std::nan(""));
    session.seek(std::numeric_limits<double>::infinity());
  };
  AtTick<decltype(bad)> at(20, bad);
  session.add_observer(at);
  ASSERT_FALSE(session.start_links());
  session.begin();
  (void)session.run(no_interrupts);
  const std::vector<Kept> kept = all.kept();
  ASSERT_EQ(kept[21].commands.size(), 3u);
  EXPECT_EQ(kept[21].commands[0].outcome, CommandOutcome::bad_channel);
  EXPECT_EQ(kept[21].commands[1].outcome, CommandOutcome::bad_value);
  EXPECT_EQ(kept[21].commands[2].outcome, CommandOutcome::bad_value);
}

TEST(ShowSession, EstopFromAnotherThreadFaults) {
  Figure f;
  ShowSession session(f.rig, f.show, stepped_config());
  KeepAll all;
  session.add_observer(all);
  // Another thread presses the e-stop between ticks 80 and 81.
  auto press = [&](const TickRecord&) { std::thread([&] { session.estop(); }).join(); };
  AtTick<decltype(press)> at(80, press);
  session.add_observer(at);
  ASSERT_FALSE(session.start_links());
  session.begin();
  (void)session.run(no_interrupts);
  const std::vector<Kept> kept = all.kept();
  EXPECT_FALSE(kept[80].estop);
  EXPECT_TRUE(kept[81].estop);
  EXPECT_EQ(kept[81].phase, control::Phase::faulted);
  EXPECT_EQ(kept[81].fault, control::FaultCause::estop);
  EXPECT_EQ(session.controller().latched_fault().cause, control::FaultCause::estop);
  EXPECT_EQ(kept.back().phase, control::Phase::faulted);
  EXPECT_LT(kept.size(), 50u * 12u);  // the show did not play on
}

TEST(ShowSession, CommandsFromOtherThreadsWhileTheLoopRunsInRealTime) {
  Figure f;
  // A one-second show at 200 Hz on the real-time clock, the loop on its own thread.
  const playback::Show show = config::load_show_text(
      "name: short\nduration: 1\ntracks:\n  neck_pan:\n    - {time: 0, value: 0}\n    - {time: 1, value: 40}\n", "short.yaml");
  SessionConfig config;
  config.rate_hz = 200;
  config.links.simulate_all = true;
  config.realtime = control::RealtimeRequest{0, false, -1};
  ShowSession session(f.rig, show, config);
  KeepAll all;
  session.add_observer(all);
  ASSERT_FALSE(session.start_links());
  session.begin();
  std::atomic<bool> done{false};
  std::vector<std::thread> senders;
  std::atomic<std::uint64_t> pushed{0};
  for (int t = 0; t < 3; ++t)
    senders.emplace_back([&, t] {
      for (int i = 0; !done.load() && i < 20000; ++i) {
        const std::size_t channel = static_cast<std::size_t>(i + t) % f.rig.channels.size();
        const bool ok = (i % 2 == 0) ? session.hold(channel, 5.0 * t) : session.release(channel);
        if (ok) pushed.fetch_add(1);
        std::this_thread::yield();
      }
    });
  const control::RunResult run = session.run(no_interrupts);
  done.store(true);
  for (std::thread& s : senders) s.join();
  const std::vector<Kept> kept = all.kept();
  EXPECT_EQ(kept.size() + session.records_dropped(), run.ticks);
  std::uint64_t taken = 0;
  for (const Kept& k : kept) {
    taken += k.commands.size();
    for (const CommandRecord& c : k.commands) EXPECT_EQ(c.outcome, CommandOutcome::applied);
    for (std::size_t c = 0; c < f.rig.channels.size(); ++c) {
      EXPECT_GE(k.channels[c].command, f.rig.channels[c].min);
      EXPECT_LE(k.channels[c].command, f.rig.channels[c].max);
    }
  }
  EXPECT_GT(taken, 0u);
  EXPECT_LE(taken, pushed.load());
  EXPECT_EQ(kept.back().phase, control::Phase::disabled);
}

}  // namespace
}  // namespace avar::session
