// avar-bench-input: live input to command latency at 1 kHz. An OSC sender on loopback UDP sends
// a control every 3.7 ms (never in step with the tick); avar's OSC input (liblo, its own thread)
// posts it to the mailbox; the 1 kHz loop (run_loop on the wall clock) mixes it and sends the
// frame. Measured per message, on CLOCK_MONOTONIC:
//   arrival -> send: the input thread's receipt to the link's send() in the tick that took it
//                    (what the input path adds; includes waiting for the next tick, up to 1 ms)
//   sender  -> send: from the sender's sendto(), UDP and liblo included
// and, beside them, the peer floor: the same sender to a bare blocking recvfrom() thread.
// Usage: avar-bench-input [SECONDS, default 10]
#include <lo/lo.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "avar/control/controller.hpp"
#include "avar/control/live_inputs.hpp"
#include "avar/control/runner.hpp"
#include "avar/inputs/input_source_factory.hpp"
#include "support/osc_sender.hpp"

namespace {

using namespace avar;

constexpr std::size_t kMaxMessages = 1 << 20;

/// Sender timestamps by message number (the message's float value).
struct SendLog {
  std::unique_ptr<std::atomic<std::int64_t>[]> sent_ns { new std::atomic<std::int64_t>[ kMaxMessages ] };
};

/// Sends /avar/control/x with values 1, 2, 3... every `period_us`, logging each send time.
void send_messages(int port, double seconds, int period_us, SendLog& log, std::atomic<std::size_t>& count) {
  lo_address to = lo_address_new("127.0.0.1", std::to_string(port).c_str());
  const std::int64_t end = control::monotonic_ns() + static_cast<std::int64_t>(seconds * 1e9);
  for (std::size_t i = 1; i < kMaxMessages && control::monotonic_ns() < end; ++i) {
    log.sent_ns[i].store(control::monotonic_ns(), std::memory_order_release);
    lo_send(to, "/avar/control/x", "f", static_cast<float>(i));
    count.store(i, std::memory_order_release);
    std::this_thread::sleep_for(std::chrono::microseconds(period_us));
  }
  lo_address_free(to);
}

/// The link at the end of the tick: stamps the send of every frame that carries a new message.
class StampingLink final : public firmware_iface::ActuatorLink {
 public:
  StampingLink(const control::LiveInputs& live, const SendLog& log, std::size_t expected)
      : live_(live), log_(log), slot_(live.mailbox().find("x")) {
    from_arrival_.reserve(expected);
    from_sender_.reserve(expected);
  }
  Status start() override { return Status::ok; }
  Status read_positions(std::span<double>, std::span<bool>) override { return Status::ok; }
  Status send(std::span<const double>) noexcept override {
    const std::int64_t now = control::monotonic_ns();
    const control::ControlReading r = live_.mailbox().read(slot_);
    const double taken = live_.control_values()[slot_];  // what this tick mixed
    if (r.sequence == 0 || !(taken > last_)) return Status::ok;
    last_ = taken;
    const auto id = static_cast<std::size_t>(taken);
    if (from_arrival_.size() < from_arrival_.capacity() && r.value == taken) from_arrival_.push_back(now - r.arrived_ns);
    if (from_sender_.size() < from_sender_.capacity())
      from_sender_.push_back(now - log_.sent_ns[id].load(std::memory_order_acquire));
    return Status::ok;
  }
  Status release() noexcept override { return Status::ok; }
  void release_channel(std::size_t) noexcept override {}
  std::uint64_t saturated_pulses() const noexcept override { return 0; }
  const std::string& describe() const noexcept override { return name_; }

  std::vector<std::int64_t> from_arrival_, from_sender_;

 private:
  const control::LiveInputs& live_;
  const SendLog& log_;
  std::size_t slot_;
  double last_ = 0;
  std::string name_ = "stamping link";
};

void print_row(const char* what, std::vector<std::int64_t> ns) {
  if (ns.empty()) {
    std::printf("input,%s,samples=0\n", what);
    return;
  }
  std::sort(ns.begin(), ns.end());
  const auto at = [&](double q) {
    return static_cast<double>(ns[static_cast<std::size_t>(q * static_cast<double>(ns.size() - 1))]) / 1e3;
  };
  std::printf("input,%s,samples=%zu,p50_us=%.1f,p99_us=%.1f,max_us=%.1f\n", what, ns.size(), at(0.5), at(0.99),
              static_cast<double>(ns.back()) / 1e3);
}

}  // namespace

int main(int argc, char** argv) {
  double seconds = 10;
  if (argc > 1) {
    const std::string arg = argv[1];
    if (arg == "--help" || arg == "-h") {
      std::printf("usage: avar-bench-input [SECONDS]   (default 10 s of messages for each measurement)\n");
      return 0;
    }
    seconds = std::atof(argv[1]);
    if (!(seconds > 0)) {
      std::fprintf(stderr, "avar-bench-input: expected a positive number of seconds, got '%s'\n", argv[1]);
      return 2;
    }
  }
  constexpr double kRate = 1000;
  constexpr int kPeriodUs = 3700;
  const auto expected = static_cast<std::size_t>(seconds * 1e6 / kPeriodUs) + 16;

  // Peer floor: the same sender to a bare recvfrom().
  {
    int port = 0;
    const int fd = avar::testing::bound_udp_socket(port);
    SendLog log;
    std::vector<std::int64_t> floor;
    floor.reserve(expected);
    std::atomic<std::size_t> sent{0};
    std::thread receiver([&] {
      char buf[256];
      for (;;) {
        const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
        const std::int64_t now = control::monotonic_ns();
        if (n <= 0) return;
        lo_message m = lo_message_deserialise(buf, static_cast<std::size_t>(n), nullptr);
        if (!m) continue;
        const auto id = static_cast<std::size_t>(lo_message_get_argv(m)[0]->f);
        lo_message_free(m);
        if (id == 0) return;
        if (floor.size() < floor.capacity()) floor.push_back(now - log.sent_ns[id].load(std::memory_order_acquire));
      }
    });
    send_messages(port, seconds, kPeriodUs, log, sent);
    lo_address to = lo_address_new("127.0.0.1", std::to_string(port).c_str());
    lo_send(to, "/avar/control/x", "f", 0.0f);  // ends the receiver
    lo_address_free(to);
    receiver.join();
    ::close(fd);
    print_row("peer=bare_udp_recv,sender_to_recv", floor);
  }

  // avar: OSC input -> mailbox -> 1 kHz tick -> send.
  rig::Rig rig;
  rig.name = "bench-input";
  rig.channels.push_back({.name = "x",
                          .unit = "",
                          .min = 0,
                          .max = 1e7,
                          .rest = 0,
                          .max_velocity = 1e9,
                          .max_acceleration = 1e12,
                          .max_jerk = 1e15,
                          .ramp_velocity = 1e7,
                          .where = {}});
  playback::Show show;
  show.name = "live";
  show.duration = seconds + 2;
  control::ControlMapping m;
  m.control = "x";
  m.low = 0;
  m.high = 1e7;
  m.shape.input = std::pair{0.0, 1e7};
  m.crossfade_s = 0;
  control::LiveInputs live({{"x", 0, 1e7}}, {m});
  SendLog log;
  StampingLink link(live, log, expected);
  const int port = avar::testing::free_udp_port();
  auto osc = inputs::make_input_source("osc://127.0.0.1:" + std::to_string(port));
  osc->start(live.sink());
  control::ControllerOptions options;
  options.tick_period_s = 1 / kRate;
  options.live = &live;
  options.min_ramp_s = 0.01;
  control::Controller controller(rig, show, {&link}, options);
  const std::vector<double> rest{0};
  controller.begin(0, rest);
  std::atomic<std::size_t> sent{0};
  std::thread sender([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(500));  // past the soft start
    send_messages(port, seconds, kPeriodUs, log, sent);
  });
  class Quiet final : public control::TickObserver {
   public:
    void after_tick(std::uint64_t, double, double, double, control::Controller&) override {}
  } quiet;
  const std::atomic<int> no_interrupts{0};
  const control::RunResult run = control::run_loop(
      controller, {kRate, control::ClockMode::realtime, control::RealtimeRequest{50, true, -1}}, quiet, no_interrupts);
  sender.join();
  osc->stop();
  for (const auto& w : run.realtime.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  std::printf("input,rate_hz=%.0f,messages=%zu,ticks=%llu,deadline_misses=%llu,osc_ignored=%llu\n", kRate, sent.load(),
              static_cast<unsigned long long>(run.ticks), static_cast<unsigned long long>(run.deadline_misses),
              static_cast<unsigned long long>(osc->counters().ignored));
  print_row("avar,arrival_to_send", link.from_arrival_);
  print_row("avar,sender_to_send", link.from_sender_);
  return 0;
}
