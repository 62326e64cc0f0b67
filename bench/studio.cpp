// avar-bench-studio: the studio's server under a client's hand, on the simulated hello-head at the
// rig's rate, in real time, over a real WebSocket on loopback.
// - Glass to wire: a slider's hold message sent -> the first tick whose frame carries it (the
//   frame the links send at that tick). Median, p95 and worst over N holds, each sent at a random
//   phase of the tick. Target: p95 <= 30 ms.
// - Glass to wire from the glass: the same from a real pointerdown on the jaw's slider in the
//   studio's page (headless Chromium, bench/browser/studio_glass.mjs; its event time stamp) to
//   the moment the simulated Maestro behind the serial port holds the new target (the bytes of
//   that tick read and parsed; watched every 100 us). Skipped, with the reason, without the built
//   page, node or Chromium.
// - Scrubbing back and forth at 10 Hz: scrub messages jumping between the show's two ends, every
//   tick's commands checked against each channel's range, speed and acceleration limits.
//   Target: 0 commands outside any limit.
// Usage: avar-bench-studio [--holds N] [--pointer-holds N] [--scrub-seconds S] [--status-hz R]
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sys/wait.h>
#include <mutex>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "avar/config/rig_file.hpp"
#include "avar/config/show_file.hpp"
#include "avar/sim/sim_maestro.hpp"
#include "avar/studio/server.hpp"
#include "avar/studio/studio_run.hpp"
#include "support/studio_client.hpp"

namespace {

using namespace avar;
using Clock = std::chrono::steady_clock;

std::string example(const std::string& path) { return std::string(AVAR_SOURCE_DIR) + "/examples/" + path; }

/// On the loop thread, right after each tick's send: when the watched channel's target first left
/// its resting value since the last arm().
class Departure final : public control::TickObserver {
 public:
  Departure(std::size_t channel, double rest) : channel_(channel), rest_(rest) {}
  void arm() { departed_ns_.store(0); }
  std::int64_t departed_ns() const { return departed_ns_.load(); }
  bool at_rest() const { return at_rest_.load(); }
  void after_tick(std::uint64_t, double, double, double, control::Controller& controller) override {
    const double target = controller.target()[channel_];
    at_rest_.store(controller.phase() == control::Phase::running && target == rest_ && controller.commanded()[channel_] == rest_);
    if (target != rest_ && departed_ns_.load() == 0) departed_ns_.store(Clock::now().time_since_epoch().count());
  }

 private:
  std::size_t channel_;
  double rest_;
  std::atomic<std::int64_t> departed_ns_{1};
  std::atomic<bool> at_rest_{false};
};

/// On the publisher thread: every tick's commands against the rig's limits.
class LimitCheck final : public session::SessionObserver {
 public:
  LimitCheck(const rig::Rig& rig, double dt) : rig_(rig), dt_(dt) {}
  void on_tick(const session::TickRecord& r) override {
    if (!counting_.load()) return;
    ++ticks_;
    for (std::size_t c = 0; c < r.channels.size(); ++c) {
      const rig::ChannelSpec& spec = rig_.channels[c];
      const double x = r.channels[c].command;
      if (x < spec.min || x > spec.max) ++out_of_range_;
      if (have_ >= 1 && std::abs(x - last_[c]) > spec.max_velocity * dt_ * (1 + 1e-9)) ++too_fast_;
      if (have_ >= 2 && std::abs(x - 2 * last_[c] + before_[c]) > spec.max_acceleration * dt_ * dt_ * (1 + 1e-9)) ++too_sharp_;
    }
    before_ = last_;
    last_.assign(r.channels.size(), 0);
    for (std::size_t c = 0; c < r.channels.size(); ++c) last_[c] = r.channels[c].command;
    have_ = std::min(have_ + 1, 2);
  }
  void start() { counting_.store(true); }
  void stop() { counting_.store(false); }
  std::uint64_t ticks_ = 0, out_of_range_ = 0, too_fast_ = 0, too_sharp_ = 0;

 private:
  const rig::Rig& rig_;
  double dt_;
  std::atomic<bool> counting_{false};
  std::vector<double> last_, before_;
  int have_ = 0;
};

/// Every moment (system clock, ns since the epoch) the simulated device's target for one servo
/// changed after holding still for at least kSettled: a press on a figure at rest, whatever its
/// resting target is. Watched from a thread of its own under the device host's lock.
class DeviceDepartures {
 public:
  /// Longer than a tick (the glide back to rest changes the target every tick), shorter than
  /// the rest the page waits for before each press.
  static constexpr std::chrono::milliseconds kSettled{45};

  DeviceDepartures(assembly::FigureLinks& figure, std::size_t link, int servo)
      : figure_(figure), link_(link), servo_(servo), thread_([this] { watch(); }) {}
  ~DeviceDepartures() {
    stop_.store(true);
    thread_.join();
  }
  std::vector<std::int64_t> taken() {
    const std::lock_guard lock(mutex_);
    return departures_;
  }

 private:
  std::uint16_t target() {
    std::uint16_t t = 0;
    figure_.with_simulated(link_, [&](sim::ByteDevice& d) { t = dynamic_cast<sim::SimMaestro&>(d).target(servo_); });
    return t;
  }
  void watch() {
    std::uint16_t last = target();
    auto still_since = std::chrono::system_clock::now();
    while (!stop_.load()) {
      const std::uint16_t now_target = target();
      if (now_target != last) {
        const auto now = std::chrono::system_clock::now();
        if (now - still_since >= kSettled) {
          const std::lock_guard lock(mutex_);
          departures_.push_back(now.time_since_epoch().count());
        }
        last = now_target;
        still_since = now;
      }
      std::this_thread::sleep_for(std::chrono::microseconds(100));
    }
  }
  assembly::FigureLinks& figure_;
  std::size_t link_;
  int servo_;
  std::atomic<bool> stop_{false};
  std::mutex mutex_;
  std::vector<std::int64_t> departures_;
  std::thread thread_;
};

/// The pointer half in Chromium (studio_glass.mjs): each press's time (system clock, ms), less
/// the page's clock skew. Empty, with `why` said, when it cannot run.
std::vector<double> pointer_presses([[maybe_unused]] const std::string& url, [[maybe_unused]] int holds, std::string& why) {
#ifndef AVAR_BENCH_NODE
  why = "node was not found when avar was configured";
  return {};
#else
  const std::string command = std::string(AVAR_BENCH_NODE) + " " + AVAR_SOURCE_DIR "/bench/browser/studio_glass.mjs --url '" +
                              url + "' --modules " AVAR_SOURCE_DIR "/studio/page --holds " + std::to_string(holds) + " 2>&1";
  FILE* child = popen(command.c_str(), "r");
  if (!child) {
    why = "could not start node";
    return {};
  }
  std::vector<double> presses;
  double skew = 0;
  std::string last, said;  // the last line, and every line that is not a measurement
  char line[512];
  while (std::fgets(line, sizeof line, child)) {
    last = line;
    if (std::sscanf(line, "skew %lf", &skew) == 1) continue;
    double at = 0;
    if (std::sscanf(line, "pointer %lf", &at) == 1) presses.push_back(at - skew);
    else if (last != "done\n") said += "  " + last;
  }
  const int status = pclose(child);
  if (WIFEXITED(status) && WEXITSTATUS(status) == 77) why = "no Chromium (" + last.substr(0, last.find('\n')) + ")";
  else if (status != 0) why = "the page's run failed:\n" + said;
  return presses;
#endif
}

double percentile(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(
      std::min<double>(static_cast<double>(v.size()) - 1, std::ceil(p * static_cast<double>(v.size())) - 1))];
}

}  // namespace

int main(int argc, char** argv) {
  int holds = 100;
  int pointer_holds = 100;
  double scrub_seconds = 60;
  studio::ServerOptions server_options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--holds" && i + 1 < argc) {
      holds = std::atoi(argv[++i]);
    } else if (arg == "--pointer-holds" && i + 1 < argc) {
      pointer_holds = std::atoi(argv[++i]);
    } else if (arg == "--scrub-seconds" && i + 1 < argc) {
      scrub_seconds = std::atof(argv[++i]);
    } else if (arg == "--status-hz" && i + 1 < argc) {
      server_options.status_hz = std::atof(argv[++i]);
    } else {
      std::printf(
          "usage: avar-bench-studio [--holds N] [--scrub-seconds S]\n"
          "  --holds N          slider holds timed from message to wire (default 100)\n"
          "  --pointer-holds N  slider presses in Chromium timed from the pointer event to the device (default 100; 0: none)\n"
          "  --scrub-seconds S  scrubbing back and forth at 10 Hz for S seconds (default 60)\n"
          "  --status-hz R      status messages a second from the server (default 20)\n");
      return arg == "--help" || arg == "-h" ? 0 : 2;
    }
  }
  if (holds < 1 || !(scrub_seconds > 0)) {
    std::fprintf(stderr, "avar-bench-studio: expected a positive count of holds and of seconds\n");
    return 2;
  }

  const rig::Rig rig = config::load_rig_file(example("rigs/hello-head.yaml"));
  studio::Studio studio(rig, edit::ShowDocument::open(example("shows/hello-head.yaml")), "");
  session::SessionConfig config;
  config.rate_hz = rig.rate_hz;
  config.links.simulate_all = true;
  config.hold_at_end = true;
  config.start_paused = true;
  session::ShowSession session(rig, studio.initial_show(), config);
  const std::size_t jaw = *rig.find_channel("jaw");
  Departure departure(jaw, 0.0);
  LimitCheck limits(rig, 1.0 / config.rate_hz);
  session.set_loop_observer(&departure);
  session.add_observer(studio);
  session.add_observer(limits);
  studio.attach(&session);
  if (session.start_links()) {
    std::fprintf(stderr, "avar-bench-studio: the simulated links did not start\n");
    return 1;
  }
  session.begin();
  server_options.assets_dir = studio::built_page_dir();
  studio::Server server(studio, server_options);
  std::atomic<int> interrupts{0};
  std::thread runner([&] { (void)session.run(interrupts); });
  avar::testing::StudioClient client(server.port(), "/ws");
  if (!client.connected() || !client.next("hello")) {
    std::fprintf(stderr, "avar-bench-studio: could not connect: %s\n", client.error().c_str());
    session.stop();
    runner.join();
    return 1;
  }
  const auto wait_until = [](const auto& done, std::chrono::milliseconds limit) {
    const auto deadline = Clock::now() + limit;
    while (!done() && Clock::now() < deadline) std::this_thread::sleep_for(std::chrono::microseconds(200));
    return done();
  };
  // Homed (holds act on the running show), paused at 0 s.
  wait_until([&] { return departure.at_rest(); }, std::chrono::seconds(10));

  // Glass to wire.
  std::mt19937 rng(20261206);
  std::uniform_int_distribution<int> phase_us(0, static_cast<int>(2e6 / config.rate_hz));
  std::vector<double> latency_ms;
  for (int i = 0; i < holds; ++i) {
    std::this_thread::sleep_for(std::chrono::microseconds(phase_us(rng)));
    departure.arm();
    const std::int64_t sent = Clock::now().time_since_epoch().count();
    client.send(R"({"type": "hold", "channel": "jaw", "value": 15})");
    if (!wait_until([&] { return departure.departed_ns() != 0; }, std::chrono::seconds(1))) {
      std::fprintf(stderr, "avar-bench-studio: hold %d never reached the wire\n", i);
      break;
    }
    latency_ms.push_back(static_cast<double>(departure.departed_ns() - sent) / 1e6);
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    client.send(R"({"type": "release", "channel": "jaw"})");
    wait_until([&] { return departure.at_rest(); }, std::chrono::seconds(2));
  }

  // Glass to wire from the glass: a pointerdown in the page to the device holding the target.
  std::vector<double> pointer_ms;
  std::string pointer_skipped;
  if (pointer_holds > 0 && server_options.assets_dir.empty()) pointer_skipped = "the studio's page is not built";
  else if (pointer_holds > 0) {
    const auto actuator = std::find_if(rig.actuators.begin(), rig.actuators.end(),
                                       [&](const rig::ActuatorSpec& a) { return a.channel.value == jaw; });
    DeviceDepartures departures(session.figure(), actuator->link.value, actuator->device_channel);
    const std::vector<double> presses = pointer_presses(server.url(), pointer_holds, pointer_skipped);
    const std::vector<std::int64_t> taken = departures.taken();
    // Each press's latency: to the first departure after it.
    for (const double press : presses) {
      const auto first =
          std::find_if(taken.begin(), taken.end(), [&](std::int64_t t) { return static_cast<double>(t) / 1e6 >= press; });
      if (first != taken.end()) pointer_ms.push_back(static_cast<double>(*first) / 1e6 - press);
    }
    if (pointer_skipped.empty() && pointer_ms.size() != static_cast<std::size_t>(pointer_holds))
      pointer_skipped = std::to_string(presses.size()) + " presses made, " + std::to_string(taken.size()) + " departures seen, " +
                        std::to_string(pointer_ms.size()) + " paired; expected " + std::to_string(pointer_holds) + " of each";
  }

  // Scrubbing back and forth at 10 Hz between the show's ends.
  limits.start();
  const auto scrubs = static_cast<int>(scrub_seconds * 10);
  auto next = Clock::now();
  for (int i = 0; i < scrubs; ++i) {
    client.send(std::string(R"({"type": "scrub", "time": )") + (i % 2 ? "11.5" : "0.5") + "}");
    next += std::chrono::milliseconds(100);
    std::this_thread::sleep_until(next);
  }
  limits.stop();
  session.stop();
  runner.join();

  if (!latency_ms.empty()) {
    std::printf(
        "glass to wire (hold message -> the tick whose frame carries it), %zu holds at %g Hz: median %.2f ms, "
        "p95 %.2f ms, worst %.2f ms (target p95 <= 30 ms)\n",
        latency_ms.size(), config.rate_hz, percentile(latency_ms, 0.5), percentile(latency_ms, 0.95),
        percentile(latency_ms, 1.0));
  }
  if (!pointer_ms.empty())
    std::printf(
        "glass to wire from the glass (pointerdown on the jaw's slider in Chromium -> the simulated Maestro holds the new "
        "target), %zu presses: median %.2f ms, p95 %.2f ms, worst %.2f ms (target p95 <= 30 ms)\n",
        pointer_ms.size(), percentile(pointer_ms, 0.5), percentile(pointer_ms, 0.95), percentile(pointer_ms, 1.0));
  if (!pointer_skipped.empty()) std::printf("glass to wire from the glass: %s\n", pointer_skipped.c_str());
  std::printf(
      "scrubbing at 10 Hz for %g s (%d jumps between 0.5 s and 11.5 s): %llu ticks, %llu commands outside a channel's "
      "range, %llu faster than its max_velocity, %llu beyond its max_acceleration (target 0); records dropped %llu\n",
      scrub_seconds, scrubs, static_cast<unsigned long long>(limits.ticks_),
      static_cast<unsigned long long>(limits.out_of_range_), static_cast<unsigned long long>(limits.too_fast_),
      static_cast<unsigned long long>(limits.too_sharp_), static_cast<unsigned long long>(session.records_dropped()));
  return 0;
}
