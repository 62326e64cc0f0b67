// A figure run through the library alone: waiting for the rig's start button (pressed,
// interrupted, refused while the e-stop is held, no button at all) on the simulated haunt prop,
// and the take of a recorded run (a channel performed over OSC, fitted, written, read back,
// alone or merged over the show) on the simulated hello-head.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "avar/assembly/gpio_chips.hpp"
#include "avar/config/input_map.hpp"
#include "avar/config/show_file.hpp"
#include "avar/edit/show_document.hpp"
#include "avar/session/figure_run.hpp"
#include "avar/session/play_recorder.hpp"
#include "avar/session/take.hpp"
#include "session_fixture.hpp"
#include "support/osc_sender.hpp"
#include "support/temp_file.hpp"

// A namespace of its own: the suite builds as one unity source with the other session tests.
namespace avar::session::figure_run_test {
namespace {

using test_support::example;
using test_support::Script;

// The haunt prop's buttons (examples/rigs/haunt-prop.yaml): to ground on pulled-up lines.
constexpr unsigned kEstopLine = 4;
constexpr unsigned kStartLine = 5;

struct HauntProp {
  rig::Rig rig = config::load_rig_file(example("rigs/haunt-prop.yaml"));
  playback::Show show = config::load_show_file(example("shows/haunt-prop.yaml"));
  std::shared_ptr<assembly::GpioChips> chips = std::make_shared<assembly::GpioChips>(true);

  std::unique_ptr<FigureRun> open() {
    FigureRunSetup setup;
    setup.session.rate_hz = 50;
    setup.session.stepped = true;
    setup.session.links.simulate_all = true;
    setup.session.links.gpio_chips = chips;
    auto run = std::make_unique<FigureRun>(rig, show, config::InputMap{}, std::move(setup));
    run->watch_inputs();
    return run;
  }
  void press(unsigned line) { chips->simulated("sim").set_level(line, false); }
};

TEST(FigureRun, AStartButtonPressEndsTheWaitAndTheShowThenPlays) {
  HauntProp prop;
  const std::unique_ptr<FigureRun> run = prop.open();
  EXPECT_EQ(run->start_button_names(), "'start'");
  // Pressed from another thread, as a visitor does while the figure waits; the wait ends on the
  // press whether it comes before or during the wait (the input thread counts presses).
  std::thread presser([&] { prop.press(kStartLine); });
  const std::atomic<int> interrupts{0};
  const StartWait waited = run->wait_for_start_button(interrupts);
  presser.join();
  EXPECT_EQ(waited, StartWait::pressed);

  ASSERT_FALSE(run->start());
  const control::RunResult result = run->run(interrupts, nullptr);
  EXPECT_FALSE(result.interrupted);
  EXPECT_EQ(run->session().controller().latched_fault().cause, control::FaultCause::none);
}

TEST(FigureRun, CtrlCBeforeTheStartButtonGivesUpTheWait) {
  HauntProp prop;
  const std::unique_ptr<FigureRun> run = prop.open();
  const std::atomic<int> interrupts{1};  // Ctrl-C came while nothing was pressed
  EXPECT_EQ(run->wait_for_start_button(interrupts), StartWait::interrupted);
}

TEST(FigureRun, AHeldEstopRefusesTheStart) {
  HauntProp prop;
  prop.press(kEstopLine);
  const std::unique_ptr<FigureRun> run = prop.open();
  const std::atomic<int> interrupts{0};
  EXPECT_EQ(run->wait_for_start_button(interrupts), StartWait::estop);
}

TEST(FigureRun, ARigWithoutAStartButtonHasNoneToWaitFor) {
  const rig::Rig rig = config::load_rig_file(example("rigs/hello-head.yaml"));
  const playback::Show show = config::load_show_file(example("shows/hello-head.yaml"));
  FigureRunSetup setup;
  setup.session.stepped = true;
  setup.session.links.simulate_all = true;
  FigureRun run(rig, show, config::InputMap{}, std::move(setup));
  run.watch_inputs();
  EXPECT_EQ(run.start_button_names(), "");
  const std::atomic<int> interrupts{0};
  EXPECT_EQ(run.wait_for_start_button(interrupts), StartWait::no_button);
}

/// A stepped run at 50 Hz on the simulator, with live inputs from OSC on `port`.
FigureRunSetup stepped_osc_setup(int port) {
  FigureRunSetup setup;
  setup.session.rate_hz = 50;
  setup.session.stepped = true;
  setup.session.links.simulate_all = true;
  setup.input_uris = {"osc://127.0.0.1:" + std::to_string(port)};
  return setup;
}

/// A recorder that keeps every tick's samples of `run`, for a take.
RecorderOptions keeping_recorder(const rig::Rig& rig, const playback::Show& show, const FigureRun& run) {
  RecorderOptions options;
  options.channels = rig.channels.size();
  options.links = rig.links.size();
  options.controls = run.recorded_controls();
  options.show_duration_s = show.duration;
  options.keep_samples = true;
  options.expected_ticks = 200;
  return options;
}

/// A stepped run of hello-head's live-only show with the jaw performed over OSC: a ramp of
/// values sent from tick 10 to tick 60 of the running phase, then a stop at tick 100. The
/// recorder kept every tick.
struct PerformedRun {
  rig::Rig rig = config::load_rig_file(example("rigs/hello-head.yaml"));
  playback::Show show;
  std::unique_ptr<FigureRun> run;
  std::unique_ptr<PlayRecorder> recorder;
  control::RunResult result;

  /// `over_show`: under hello-head's show (its jaw track overridden by the performance);
  /// else a live-only run.
  PerformedRun(bool perform, bool over_show)
      : show(over_show ? config::load_show_file(example("shows/hello-head.yaml")) : live_only_show(std::nullopt)) {
    const int port = testing::free_udp_port();
    run = std::make_unique<FigureRun>(rig, show, config::InputMap{}, stepped_osc_setup(port));
    recorder = std::make_unique<PlayRecorder>(keeping_recorder(rig, show, *run));
    run->session().add_observer(*recorder);

    testing::OscSender osc(port);
    LiveSession& live = *run->live();
    const std::size_t slot = live.inputs().mailbox().find("channel/jaw");
    EXPECT_LT(slot, live.inputs().mailbox().size());
    std::uint64_t t0 = 0;
    std::uint64_t sent = 0;
    Script script([&](const TickRecord& r) {
      if (t0 == 0 && r.phase == control::Phase::running) t0 = r.tick;
      if (t0 == 0) return;
      if (perform && r.tick >= t0 + 10 && r.tick <= t0 + 60) {
        EXPECT_TRUE(osc.send("/avar/channel/jaw", static_cast<float>(r.tick - t0 - 10) * 0.4f));
        // Wait for the value to reach the mailbox, so that the next tick takes it (bounded).
        ++sent;
        const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(5);
        while (live.inputs().mailbox().read(slot).sequence < sent && std::chrono::steady_clock::now() < give_up)
          std::this_thread::yield();
      }
      if (r.tick == t0 + 100) run->session().stop();
    });
    run->session().add_observer(script);
    EXPECT_FALSE(run->start());
    const std::atomic<int> interrupts{0};
    result = run->run(interrupts, nullptr);
    recorder->finish(run->session().controller());
  }

  TakeReport take(const TakeOptions& options) const {
    return write_take(options, rig, show, run->session().controller(), *recorder, run->live()->inputs());
  }
};

TEST(FigureRunTake, APerformedChannelIsFittedWrittenAndReadBackWithinTheTolerance) {
  const PerformedRun performed(true, false);
  const std::string path = testing::temp_path("jaw-take.yaml");
  std::filesystem::remove(path);
  const TakeReport report = performed.take({path, 0.1, false});

  ASSERT_EQ(report.tracks.size(), 1u);
  EXPECT_EQ(report.tracks[0].channel, "jaw");
  EXPECT_GE(report.tracks[0].keys, 2u);
  EXPECT_LE(report.tracks[0].max_error, 0.1);
  EXPECT_GT(report.ticks, 90u);
  EXPECT_GT(report.duration_s, 1.8);

  const playback::Show written = config::load_show_file(path);
  EXPECT_EQ(written.name, std::filesystem::path(path).stem().string());
  EXPECT_DOUBLE_EQ(written.duration, report.duration_s);
  ASSERT_EQ(written.tracks.size(), 1u);
  EXPECT_EQ(written.tracks[0].channel, "jaw");
  EXPECT_EQ(written.tracks[0].curve.key_count(), report.tracks[0].keys);
  // The jaw opened under the performance: the take's curve ends well away from rest.
  EXPECT_GT(written.tracks[0].curve.evaluate(report.duration_s), 5.0);
  // The take opens for editing (the studio's document) like any show: its keys are editable keys.
  edit::ShowDocument document = edit::ShowDocument::open(path);
  document.apply(edit::MoveKeys{"jaw", {1}, 0, 2.0});
  EXPECT_EQ(document.show().tracks[0].raw.keys[1].value, written.tracks[0].raw.keys[1].value + 2.0);
  ASSERT_TRUE(document.undo());
  EXPECT_FALSE(document.modified());
}

TEST(FigureRunTake, AMergedTakeIsALayerOverTheShowThatPlayed) {
  const PerformedRun performed(true, true);
  const std::string path = testing::temp_path("jaw-merged.yaml");
  const TakeReport report = performed.take({path, 0.1, true});
  const playback::Show written = config::load_show_file(path);
  ASSERT_FALSE(written.layers.empty());
  EXPECT_EQ(written.layers.back().name, "take");
  ASSERT_FALSE(written.clips.empty());
  EXPECT_EQ(written.clips.back().name, "take");
  ASSERT_EQ(written.clips.back().tracks.size(), 1u);
  EXPECT_EQ(written.clips.back().tracks[0].channel, "jaw");
  EXPECT_EQ(report.tracks.size(), 1u);
}

TEST(FigureRunTake, ASteeredTargetIsTakenAsTheJointsThatFollowedIt) {
  // The gaze head's look-around, its eyes target steered sideways by an OSC control for 1 s.
  const rig::Rig rig = config::load_rig_file(example("rigs/gaze-head.yaml"));
  const playback::Show show = config::load_show_file(example("shows/look-around.yaml"));
  const config::InputMap map = config::load_input_map(rig, example("inputs/gaze-head-stick.yaml"), true);
  const int port = testing::free_udp_port();
  FigureRun run(rig, show, map, stepped_osc_setup(port));
  PlayRecorder recorder(keeping_recorder(rig, show, run));
  run.session().add_observer(recorder);
  testing::OscSender osc(port);
  const control::ControlMailbox& mailbox = run.live()->inputs().mailbox();
  const std::size_t slot = mailbox.find("gaze_y");
  std::uint64_t t0 = 0, sent = 0;
  Script script([&](const TickRecord& r) {
    if (t0 == 0 && r.phase == control::Phase::running) t0 = r.tick;
    if (t0 == 0) return;
    if (r.tick >= t0 + 10 && r.tick <= t0 + 60) {
      EXPECT_TRUE(osc.send("/avar/control/gaze_y", 0.9f));  // far to the left
      ++sent;
      const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(5);
      while (mailbox.read(slot).sequence < sent && std::chrono::steady_clock::now() < give_up) std::this_thread::yield();
    }
    if (r.tick == t0 + 100) run.session().stop();
  });
  run.session().add_observer(script);
  ASSERT_FALSE(run.start());
  const std::atomic<int> interrupts{0};
  (void)run.run(interrupts, nullptr);
  recorder.finish(run.session().controller());
  const control::LiveInputs& live = run.live()->inputs();
  EXPECT_EQ(live.targets_touched()[0], 1);

  // On its own: the neck's channels, as they followed the steered target.
  const std::string path = testing::temp_path("gaze-take.yaml");
  const TakeReport report = write_take({path, 0.1, false}, rig, show, run.session().controller(), recorder, live);
  ASSERT_EQ(report.tracks.size(), 2u);
  EXPECT_EQ(report.tracks[0].channel, "neck_pan");
  EXPECT_EQ(report.tracks[1].channel, "neck_tilt");
  EXPECT_LE(report.tracks[0].max_error, 0.1);
  // Looking left at the steered point at some time of the take.
  const playback::Show written = config::load_show_file(path);
  double most_left = -90;
  for (double t = 0; t < written.duration; t += 0.02) most_left = std::max(most_left, written.tracks[0].curve.evaluate(t));
  EXPECT_GT(most_left, 30);
  // Merged over the show, the show's own target would override it: refused, nothing written.
  const std::string merged = testing::temp_path("gaze-merged.yaml");
  std::filesystem::remove(merged);
  try {
    (void)write_take({merged, 0.1, true}, rig, show, run.session().controller(), recorder, live);
    FAIL() << "expected the merge to be refused";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("the take steered target 'eyes'"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(merged));
}

TEST(FigureRunTake, ALiveOnlyRunHasNoShowToMergeOver) {
  const PerformedRun performed(true, false);
  const std::string path = testing::temp_path("jaw-no-merge.yaml");
  std::filesystem::remove(path);
  EXPECT_THROW(performed.take({path, 0.1, true}), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(FigureRunTake, ARunNoControlMovedKeepsNothingAndWritesNothing) {
  const PerformedRun idle(false, false);
  const std::string path = testing::temp_path("empty-take.yaml");
  std::filesystem::remove(path);
  try {
    idle.take({path, 0.1, false});
    FAIL() << "a take with no performed channel was written";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("nothing to keep: no control moved a channel"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(path + " not written"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(path));
}

}  // namespace
}  // namespace avar::session::figure_run_test
