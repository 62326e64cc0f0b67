// The cue player fires a show's OSC cues by show time: through a lead-in, seeks both ways, a
// looping show's passes and a session's loop over a show that does not loop, on a stepped session
// of the simulated hello-head. Which cue fired when is read from the datagrams on a loopback
// socket (each cue carries its own number) and the records of the ticks that fired them.
#include <gtest/gtest.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "avar/session/cue_player.hpp"
#include "session_fixture.hpp"
#include "support/osc_sender.hpp"

// A namespace of its own: the suite builds as one unity source with the other session tests.
namespace avar::session::cue_player_test {
namespace {

using test_support::example;
using test_support::Script;

constexpr double kRate = 50;

/// A show of `duration` seconds keying the neck pan, with an OSC cue at each of `times`, cue k
/// carrying the integer k.
std::string show_with_cues(int port, double duration, bool loop, const std::vector<double>& times) {
  std::string s = "name: cues\nduration: " + std::to_string(duration) + "\nloop: " + (loop ? "true" : "false") +
                  "\ntracks:\n  neck_pan:\n    - {time: 0, value: 0}\n    - {time: " + std::to_string(duration) +
                  ", value: 10}\ncues:\n";
  for (std::size_t k = 0; k < times.size(); ++k)
    s += "  - {time: " + std::to_string(times[k]) + ", osc: {to: 127.0.0.1:" + std::to_string(port) + ", address: /cue, args: [" +
         std::to_string(k) + "]}}\n";
  return s;
}

/// The integer argument of every datagram waiting on `fd` (an OSC message "/cue" ",i" int32).
std::vector<int> received_cues(int fd) {
  std::vector<int> cues;
  for (;;) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 200) != 1) break;
    unsigned char buffer[64] = {};
    if (::recv(fd, buffer, sizeof buffer, 0) != 16) break;  // "/cue\0\0\0\0" ",i\0\0" and 4 bytes
    cues.push_back((buffer[12] << 24) | (buffer[13] << 16) | (buffer[14] << 8) | buffer[15]);
  }
  return cues;
}

std::atomic<int> no_interrupts{0};

/// Runs `show` on a stepped session with `config`'s lead-in; `act` sees every record and may
/// command the session. Returns the numbers of the cues that arrived, in order, and the show
/// time of the tick that fired each (in `fired_at`).
struct CueRun {
  std::vector<int> arrived;
  std::vector<double> fired_at;
};
CueRun run_cues(const std::string& show_text, double lead_in_s, int fd,
                const std::function<void(ShowSession&, const TickRecord&)>& act) {
  const rig::Rig rig = config::load_rig_file(example("rigs/hello-head.yaml"));
  const playback::Show show = config::load_show_text(show_text, "cues.yaml");
  SessionConfig config;
  config.rate_hz = kRate;
  config.stepped = true;
  config.links.simulate_all = true;
  config.lead_in_s = lead_in_s;
  ShowSession session(rig, show, config);
  CuePlayer cues(show);
  session.set_loop_observer(&cues);
  CueRun run;
  Script script([&](const TickRecord& r) {
    while (run.fired_at.size() < cues.fired()) run.fired_at.push_back(r.show_time_s);
    act(session, r);
  });
  session.add_observer(script);
  EXPECT_FALSE(session.start_links());
  session.begin();
  (void)session.run(no_interrupts);
  cues.flush();
  EXPECT_EQ(cues.failed(), 0u);
  run.arrived = received_cues(fd);
  return run;
}

TEST(CuePlayer, FiresByShowTimeNotInTheLeadInAndSkipsWhatASeekJumpsOver) {
  int port = 0;
  const int fd = testing::bound_udp_socket(port);
  // Cues 0..4 at 0, 1, 2, 3, 4 s of a 5 s show; a 1 s lead-in. At show time 1.5 a seek to 3.5
  // (cues 2 and 3 skipped), at 4.2 a seek back to 0.5 (cues 1 to 4 fire again as show time
  // reaches them; cue 0 lies before where it landed).
  bool forward = false, back = false;
  const CueRun run = run_cues(show_with_cues(port, 5, false, {0, 1, 2, 3, 4}), 1.0, fd, [&](ShowSession& s, const TickRecord& r) {
    if (r.phase != control::Phase::running) return;
    if (!forward && r.show_time_s >= 1.5) forward = s.seek(3.5);
    if (forward && !back && r.show_time_s >= 4.2) back = s.seek(0.5);
  });
  ASSERT_TRUE(forward && back);
  EXPECT_EQ(run.arrived, (std::vector<int>{0, 1, 4, 1, 2, 3, 4}));
  // Each fired on the tick whose show time reached it: cue 0 at 0 (after the lead-in, which
  // runs at negative show time), not a second of loop time early.
  const std::vector<double> expected{0, 1, 4, 1, 2, 3, 4};
  ASSERT_EQ(run.fired_at.size(), expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k) {
    EXPECT_GE(run.fired_at[k], expected[k] - 1e-9) << "cue #" << k;
    EXPECT_LT(run.fired_at[k], expected[k] + 1.0 / kRate + 1e-9) << "cue #" << k;
  }
  ::close(fd);
}

TEST(CuePlayer, FiresOncePerPassOfALoopingShowAndOfASessionLoop) {
  int port = 0;
  const int fd = testing::bound_udp_socket(port);
  // A 2 s looping show, cues at 0 and 1.5: three passes, then stop.
  const CueRun looping = run_cues(show_with_cues(port, 2, true, {0, 1.5}), 0, fd, [&](ShowSession& s, const TickRecord& r) {
    if (r.phase == control::Phase::running && r.show_time_s >= 5.9) (void)s.stop();
  });
  EXPECT_EQ(looping.arrived, (std::vector<int>{0, 1, 0, 1, 0, 1}));

  // A 2 s show that does not loop, looped by the session: it starts over at 0 each time.
  bool looped = false;
  int wraps = 0;
  double last = 0;
  const CueRun session_loop = run_cues(show_with_cues(port, 2, false, {0, 1.5}), 0, fd, [&](ShowSession& s, const TickRecord& r) {
    if (r.phase != control::Phase::running) return;
    if (!looped) looped = s.loop(true);
    if (r.show_time_s < last) ++wraps;  // the session's clock started the show over
    last = r.show_time_s;
    if (wraps == 2 && r.show_time_s >= 1.9) (void)s.stop();
  });
  EXPECT_TRUE(looped);
  EXPECT_EQ(session_loop.arrived, (std::vector<int>{0, 1, 0, 1, 0, 1}));
  ::close(fd);
}

}  // namespace
}  // namespace avar::session::cue_player_test
