// A figure end to end through the library alone: a show session on the simulated hello-head, with
// idle life under the show, a channel taken over OSC, the show's OSC cues sent, show time chasing
// LTC timecode, a hold and a stop; and, on a second session with its own clock, a scrub. Every
// behaviour asserted is read from the records a SessionObserver got (the cues also from the
// loopback socket they were sent to).
//
// Two sessions, because the API allows no other way: a session whose show time follows an
// external clock (here the timecode chase) refuses the show-time commands (seek, scrub, pause,
// play, loop) with CommandOutcome::external_clock. So the first session chases timecode and its
// refused scrub is asserted; the second, on the session's own clock, is scrubbed.
#include <gtest/gtest.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "avar/config/input_map.hpp"
#include "avar/inputs/ltc_audio.hpp"
#include "avar/session/cue_player.hpp"
#include "avar/session/idle_session.hpp"
#include "avar/session/live_session.hpp"
#include "avar/session/timecode_run.hpp"
#include "session_fixture.hpp"
#include "support/osc_sender.hpp"
#include "support/temp_file.hpp"

// A namespace of its own: the suite builds as one unity source with the other session tests.
namespace avar::session::figure_end_to_end {
namespace {

using test_support::example;
using test_support::KeepAll;
using test_support::Kept;
using test_support::Script;

constexpr double kRate = 50;
constexpr double kDt = 1.0 / kRate;

/// A show that keys only neck_pan (0 to 40 degrees over 10 s), with two OSC cues to `cue_port` at
/// show times 3 and 3.5 s (the timecode starts the show at 2 s): the jaw is left to the
/// puppeteer, the eyes, lids and neck roll to idle life.
std::string show_text(int cue_port) {
  const std::string to = "127.0.0.1:" + std::to_string(cue_port);
  return "name: end-to-end\nduration: 10\nloop: false\ntracks:\n  neck_pan:\n    - {time: 0, value: 0}\n"
         "    - {time: 10, value: 40}\ncues:\n  - {time: 3.0, osc: {to: " +
         to + ", address: /e2e/cue, args: [1]}}\n  - {time: 3.5, osc: {to: " + to + ", address: /e2e/cue, args: [2]}}\n";
}

std::size_t channel_of(const rig::Rig& rig, const std::string& name) {
  for (std::size_t c = 0; c < rig.channels.size(); ++c)
    if (rig.channels[c].name == name) return c;
  throw std::invalid_argument(name);
}

std::size_t first_running(const std::vector<Kept>& kept) {
  for (std::size_t k = 0; k < kept.size(); ++k)
    if (kept[k].phase == control::Phase::running) return k;
  return kept.size();
}

/// Every channel's command moved at most its speed limit in a tick, stayed in its range, and no
/// record carries a fault.
void expect_within_limits(const rig::Rig& rig, const std::vector<Kept>& kept) {
  for (std::size_t c = 0; c < rig.channels.size(); ++c) {
    EXPECT_LE(test_support::largest_step(kept, c), rig.channels[c].max_velocity * kDt * (1 + 1e-9)) << rig.channels[c].name;
    for (const Kept& k : kept) {
      EXPECT_GE(k.channels[c].command, rig.channels[c].min) << rig.channels[c].name << " tick " << k.tick;
      EXPECT_LE(k.channels[c].command, rig.channels[c].max) << rig.channels[c].name << " tick " << k.tick;
    }
  }
  for (const Kept& k : kept) EXPECT_EQ(k.fault, control::FaultCause::none) << "tick " << k.tick;
}

/// The OSC addresses of the datagrams waiting on `fd`, waiting at most a second for each of
/// `expected` (they were sent before the call: the cue player flushed).
std::vector<std::string> received_addresses(int fd, std::size_t expected) {
  std::vector<std::string> addresses;
  while (addresses.size() < expected) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 1000) != 1) break;
    char buffer[512] = {};
    const ssize_t n = ::recv(fd, buffer, sizeof buffer - 1, 0);
    if (n <= 0) break;
    addresses.emplace_back(buffer);  // an OSC message opens with its address, NUL-terminated
  }
  return addresses;
}

std::atomic<int> no_interrupts{0};

TEST(FigureEndToEnd, TimecodeIdleOscCuesHoldAndStopThenAScrubbedSession) {
  const rig::Rig rig = config::load_rig_file(example("rigs/hello-head.yaml"));
  int cue_port = 0;
  const int cue_socket = testing::bound_udp_socket(cue_port);
  const playback::Show show = config::load_show_text(show_text(cue_port), "end-to-end.yaml");
  const std::size_t jaw = channel_of(rig, "jaw");
  const std::size_t pan = channel_of(rig, "neck_pan");
  const std::size_t tilt = channel_of(rig, "neck_tilt");
  const std::size_t eyes = channel_of(rig, "eyes_pan");

  // ---- The first session: show time from LTC, idle life, the jaw over OSC, cues, hold, stop.
  // 12 s of LTC from 01:00:02:00 at 25 fps, the show's zero at 01:00:00:00: show time runs 2 s
  // ahead of loop time (the file plays from loop time 0), which the session's own clock never
  // would.
  const std::string wav = testing::temp_path("ltc.wav");
  inputs::write_mono_wav(wav, inputs::encode_ltc_audio(Timecode{1, 0, 2, 0, FrameRate::fps25}, 300, 48000), 48000);
  ShowControlOptions timecode;
  timecode.source = "ltc:" + wav;
  timecode.offset = "01:00:00:00";
  TimecodeRun chase(timecode, /*fast=*/true, 1000);
  chase.start();

  const int osc_port = testing::free_udp_port();
  LiveSession live(rig, config::InputMap{}, {"osc://127.0.0.1:" + std::to_string(osc_port)});
  IdleSession idle(rig, show, /*seed=*/7);

  SessionConfig config;
  config.rate_hz = kRate;
  config.stepped = true;
  config.links.simulate_all = true;
  config.live = idle.layers(&live.inputs());
  config.external_clock = &chase.clock();
  ShowSession session(rig, show, config);

  CuePlayer cues(show);
  chase.forward_to(cues);
  session.set_loop_observer(&chase);

  KeepAll all;
  session.add_observer(all);
  // The script counts from the first running tick T0: at T0+10 the jaw is sent over OSC (and a
  // scrub asked for), at T0+40 the neck tilt is held far past its max, at T0+140 the run stops.
  constexpr std::uint64_t kOsc = 10, kHold = 40, kStop = 140;
  constexpr double kJawValue = 20;
  testing::OscSender osc(osc_port);
  const std::size_t jaw_slot = live.inputs().mailbox().find("channel/jaw");
  ASSERT_LT(jaw_slot, live.inputs().mailbox().size());
  std::uint64_t t0 = 0;
  bool osc_arrived = false;
  std::vector<double> cue_show_times;  // the show time of the tick that fired each cue
  Script script([&](const TickRecord& r) {
    while (cue_show_times.size() < cues.fired()) cue_show_times.push_back(r.show_time_s);
    if (t0 == 0 && r.phase == control::Phase::running) t0 = r.tick;
    if (t0 == 0) return;
    if (r.tick == t0 + kOsc) {
      EXPECT_TRUE(osc.send("/avar/channel/jaw", static_cast<float>(kJawValue)));
      // The message crosses a socket and the input's thread: wait for it to reach the mailbox,
      // so that the next tick takes it (bounded: a lost datagram fails the test, not hangs it).
      const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(5);
      while (live.inputs().mailbox().read(jaw_slot).sequence == 0 && std::chrono::steady_clock::now() < give_up)
        std::this_thread::yield();
      osc_arrived = live.inputs().mailbox().read(jaw_slot).sequence > 0;
      EXPECT_TRUE(session.scrub(1.0));
    }
    if (r.tick == t0 + kHold) {
      EXPECT_TRUE(session.hold(tilt, 1000));
    }
    if (r.tick == t0 + kStop) {
      EXPECT_TRUE(session.stop());
    }
  });
  session.add_observer(script);

  ASSERT_FALSE(session.start_links());
  session.begin();
  idle.watch(session.controller());
  const control::RunResult run = session.run(no_interrupts);
  cues.flush();
  live.stop();
  chase.stop();
  const std::vector<Kept> kept = all.kept();

  ASSERT_EQ(kept.size(), run.ticks);
  EXPECT_EQ(session.records_dropped(), 0u);
  const std::size_t start = first_running(kept);
  ASSERT_EQ(start, t0);
  ASSERT_GT(kept.size(), start + kStop + 1);
  expect_within_limits(rig, kept);

  // Timecode drives show time: once the chase has locked, show time is loop time + 2 s.
  for (std::size_t k = start + 25; k <= start + kStop; ++k)
    EXPECT_NEAR(kept[k].show_time_s, kept[k].now_s + 2.0, 0.05) << "tick " << k;
  // The scrub was refused, named as the external clock's doing.
  const Kept& scrubbed = kept[start + kOsc + 1];
  ASSERT_EQ(scrubbed.commands.size(), 1u);
  EXPECT_EQ(scrubbed.commands[0].command.kind, CommandKind::scrub);
  EXPECT_EQ(scrubbed.commands[0].outcome, CommandOutcome::external_clock);
  EXPECT_FALSE(scrubbed.paused);

  // The jaw follows the OSC value: within half a second, and holds it (the direct control lets
  // go only after 2 s of silence).
  ASSERT_TRUE(osc_arrived);
  for (std::size_t k = start + kOsc + 25; k <= start + kOsc + 90; ++k)
    EXPECT_NEAR(kept[k].channels[jaw].command, kJawValue, 1e-6) << "tick " << k;
  for (std::size_t k = start; k <= start + kOsc; ++k) EXPECT_NEAR(kept[k].channels[jaw].command, 0.0, 1e-9) << "tick " << k;

  // The hold: taken, clamped to the tilt's max, reached within the limits checked above.
  const Kept& held = kept[start + kHold + 1];
  ASSERT_EQ(held.commands.size(), 1u);
  EXPECT_EQ(held.commands[0].command.kind, CommandKind::hold);
  EXPECT_EQ(held.commands[0].outcome, CommandOutcome::applied);
  EXPECT_FALSE(kept[start + kHold].channels[tilt].held);
  for (std::size_t k = start + kHold + 1; k <= start + kStop; ++k) {
    EXPECT_TRUE(kept[k].channels[tilt].held) << "tick " << k;
    EXPECT_DOUBLE_EQ(kept[k].channels[tilt].target, rig.channels[tilt].max) << "tick " << k;
  }
  EXPECT_NEAR(kept[start + kStop].channels[tilt].command, rig.channels[tilt].max, 1e-6);

  // Idle life moves the eyes, which the show does not key: saccades while the show plays.
  double eyes_low = 1e9, eyes_high = -1e9;
  for (std::size_t k = start; k <= start + kStop; ++k) {
    eyes_low = std::min(eyes_low, kept[k].channels[eyes].command);
    eyes_high = std::max(eyes_high, kept[k].channels[eyes].command);
  }
  EXPECT_GT(eyes_high - eyes_low, 1.0);
  // The show still drives the neck pan: toward its key at show time (0 to 40 over 10 s).
  EXPECT_NEAR(kept[start + kStop].channels[pan].target, 4.0 * kept[start + kStop].show_time_s, 1e-6);

  // Stop: the next tick eases to rest, and the run ends.
  const Kept& stopped = kept[start + kStop + 1];
  ASSERT_EQ(stopped.commands.size(), 1u);
  EXPECT_EQ(stopped.commands[0].command.kind, CommandKind::stop);
  EXPECT_EQ(stopped.commands[0].outcome, CommandOutcome::applied);
  EXPECT_EQ(stopped.phase, control::Phase::stopping);
  EXPECT_EQ(kept.back().phase, control::Phase::disabled);
  EXPECT_LT(kept.size(), start + kStop + 5 * static_cast<std::size_t>(kRate));

  // Both cues went out to the desk's port, each on the tick whose show time (timecode's, not
  // the loop's) reached it.
  EXPECT_GT(kept[start + kStop].show_time_s, 3.5);
  ASSERT_EQ(cue_show_times.size(), 2u);
  EXPECT_GE(cue_show_times[0], 3.0);
  EXPECT_LT(cue_show_times[0], 3.1);
  EXPECT_GE(cue_show_times[1], 3.5);
  EXPECT_LT(cue_show_times[1], 3.6);
  EXPECT_EQ(cues.osc_cues(), 2u);
  EXPECT_EQ(cues.fired(), 2u);
  EXPECT_EQ(cues.sent(), 2u);
  EXPECT_EQ(cues.failed(), 0u);
  EXPECT_EQ(received_addresses(cue_socket, 2), (std::vector<std::string>{"/e2e/cue", "/e2e/cue"}));
  ::close(cue_socket);

  // ---- The second session, on its own clock: scrubbed to 8 s, the figure glides there; stop.
  SessionConfig own;
  own.rate_hz = kRate;
  own.stepped = true;
  own.links.simulate_all = true;
  ShowSession scrubbing(rig, show, own);
  KeepAll all_b;
  scrubbing.add_observer(all_b);
  constexpr std::uint64_t kScrub = 20, kScrubStop = 100;
  constexpr double kScrubTo = 8.0;
  std::uint64_t t0_b = 0;
  Script script_b([&](const TickRecord& r) {
    if (t0_b == 0 && r.phase == control::Phase::running) t0_b = r.tick;
    if (t0_b == 0) return;
    if (r.tick == t0_b + kScrub) {
      EXPECT_TRUE(scrubbing.scrub(kScrubTo));
    }
    if (r.tick == t0_b + kScrubStop) {
      EXPECT_TRUE(scrubbing.stop());
    }
  });
  scrubbing.add_observer(script_b);
  ASSERT_FALSE(scrubbing.start_links());
  scrubbing.begin();
  const control::RunResult run_b = scrubbing.run(no_interrupts);
  const std::vector<Kept> kept_b = all_b.kept();
  ASSERT_EQ(kept_b.size(), run_b.ticks);
  const std::size_t start_b = first_running(kept_b);
  ASSERT_EQ(start_b, t0_b);
  ASSERT_GT(kept_b.size(), start_b + kScrubStop + 1);
  expect_within_limits(rig, kept_b);

  const Kept& scrub = kept_b[start_b + kScrub + 1];
  ASSERT_EQ(scrub.commands.size(), 1u);
  EXPECT_EQ(scrub.commands[0].command.kind, CommandKind::scrub);
  EXPECT_EQ(scrub.commands[0].outcome, CommandOutcome::applied);
  // Before: show time ran with the loop; after: it stands at 8 s, paused.
  EXPECT_LT(kept_b[start_b + kScrub].show_time_s, 1.0);
  for (std::size_t k = start_b + kScrub + 1; k <= start_b + kScrubStop; ++k) {
    EXPECT_TRUE(kept_b[k].paused) << "tick " << k;
    EXPECT_DOUBLE_EQ(kept_b[k].show_time_s, kScrubTo) << "tick " << k;
  }
  // The neck pan's target jumped to the show's value at 8 s; its command glided there (the step
  // limit is checked above), so it trailed the target for several ticks, then arrived.
  const double pan_at_8 = 4.0 * kScrubTo;
  EXPECT_NEAR(kept_b[start_b + kScrub + 1].channels[pan].target, pan_at_8, 1e-6);
  EXPECT_GT(pan_at_8 - kept_b[start_b + kScrub + 5].channels[pan].command, 1.0);
  EXPECT_NEAR(kept_b[start_b + kScrubStop].channels[pan].command, pan_at_8, 1e-6);

  const Kept& stopped_b = kept_b[start_b + kScrubStop + 1];
  ASSERT_EQ(stopped_b.commands.size(), 1u);
  EXPECT_EQ(stopped_b.commands[0].command.kind, CommandKind::stop);
  EXPECT_EQ(stopped_b.phase, control::Phase::stopping);
  EXPECT_EQ(kept_b.back().phase, control::Phase::disabled);
}

}  // namespace
}  // namespace avar::session::figure_end_to_end
