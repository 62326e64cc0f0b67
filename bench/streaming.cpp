// avar-bench-streaming: on a 115200-baud line, the smoothest position stream avar can send (a
// Maestro fed Set Multiple Targets every tick, at 100, 200 and 500 Hz) against the curve stream
// (avar-device: knots at most 50 ms apart, sooner where the motion turns fast, 150 ms ahead, the
// board at 200 Hz with its own limits), as the tracking error of
// the simulated servos. Both are the real drivers and simulated devices (the rigs hello-head and
// streaming-head, the same servos and calibrations), driven by the real controller playing
// hello-head, over a simulated wire whose bytes arrive late as a USB serial line's do: steady
// (1 ms), a CDC-ACM adapter (1 ms plus exponential jitter of 1 ms mean, the PC's ticks up to
// 0.5 ms late) and an FTDI adapter's latency timer (1 to 17 ms, one tick in a hundred 30 ms late on
// a busy PC). Every method's servos are compared with the same servos fed the commanded motion on
// a perfect link, delayed by the method's best-fitting latency (the curve stream plays 150 ms
// behind by design; a constant delay is not error): the median and worst error over every channel
// and half millisecond, in per cent of each channel's range, and the bytes each method puts on the
// wire. The reference is the motion the controller meant: its ticks' commands at their nominal
// times joined by straight lines. Deterministic (seeded).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "avar/assembly/protocol.hpp"
#include "avar/config/rig_file.hpp"
#include "avar/config/show_file.hpp"
#include "avar/control/controller.hpp"
#include "avar/firmware_iface/wire_time.hpp"
#include "avar/sim/servo_model.hpp"

namespace {

using namespace avar;

constexpr double kStepS = 0.0005;  // the world's time step
constexpr int kBaud = 115200;

/// How late a write's bytes reach the device (seconds after the tick that wrote them), and how
/// late that tick ran.
struct Latency {
  const char* name;
  double (*delivery)(std::mt19937&);
  double (*tick_late)(std::mt19937&);
};

double steady_delivery(std::mt19937&) { return 0.001; }
double on_time(std::mt19937&) { return 0; }
double cdc_delivery(std::mt19937& r) { return 0.001 + std::exponential_distribution<double>(1000.0)(r); }
double cdc_tick(std::mt19937& r) { return std::uniform_real_distribution<double>(0, 0.0005)(r); }
double ftdi_delivery(std::mt19937& r) { return std::uniform_real_distribution<double>(0.001, 0.017)(r); }
double busy_tick(std::mt19937& r) { return std::uniform_int_distribution<int>(0, 99)(r) == 0 ? 0.030 : 0.0; }

/// A serial line on simulated time: each write reaches the device whole after its delivery delay
/// and its bytes' time at the baud rate, in order. The device answers at once (hello, queries).
class LateWire final : public firmware_iface::ByteTransport {
 public:
  LateWire(sim::ByteDevice& device, const Latency& latency, unsigned seed) : device_(device), latency_(latency), rng_(seed) {}
  Status write(std::span<const std::uint8_t> bytes) noexcept override {
    const double arrive =
        std::max(last_arrival_, now_ + latency_.delivery(rng_)) + firmware_iface::wire_seconds(bytes.size(), kBaud);
    last_arrival_ = arrive;
    pending_.push_back({arrive, std::vector<std::uint8_t>(bytes.begin(), bytes.end())});
    written_ += bytes.size();
    return Status::ok;
  }
  Status read_exact(std::span<std::uint8_t> out, std::chrono::milliseconds) noexcept override {
    deliver_all();
    return device_.take_replies(out) == out.size() ? Status::ok : Status::timeout;
  }
  Status read_some(std::span<std::uint8_t> out, std::chrono::milliseconds, std::size_t* got) noexcept override {
    deliver_all();
    *got = device_.take_replies(out);
    return *got > 0 ? Status::ok : Status::timeout;
  }
  std::chrono::nanoseconds now() const noexcept override {
    return std::chrono::nanoseconds(static_cast<std::int64_t>(now_ * 1e9));
  }
  void discard_input() noexcept override {
    std::uint8_t sink[256];
    while (device_.take_replies(sink) > 0) {
    }
  }
  Status reopen() noexcept override { return Status::ok; }
  std::uint64_t bytes_written() const noexcept override { return written_; }
  const std::string& name() const noexcept override { return name_; }

  /// Moves simulated time to `t`, handing the device each write as it arrives.
  void advance_to(double t) {
    while (now_ < t) {
      const double step = std::min(kStepS, t - now_);
      now_ += step;
      while (!pending_.empty() && pending_.front().first <= now_) {
        device_.receive(pending_.front().second);
        pending_.pop_front();
      }
      device_.advance(step);
    }
  }
  double now_s() const { return now_; }
  std::mt19937& rng() { return rng_; }

 private:
  void deliver_all() {
    while (!pending_.empty()) {
      device_.receive(pending_.front().second);
      pending_.pop_front();
    }
  }
  sim::ByteDevice& device_;
  const Latency& latency_;
  std::mt19937 rng_;
  double now_ = 0, last_arrival_ = 0;
  std::deque<std::pair<double, std::vector<std::uint8_t>>> pending_;
  std::uint64_t written_ = 0;
  std::string name_ = "late wire";
};

struct Run {
  std::vector<std::vector<double>> servo;    ///< per actuator, per step: the servo horn (channel units)
  std::vector<std::vector<double>> command;  ///< per actuator, per step: the command in force (channel units)
  double bytes_per_s = 0;
};

/// Plays hello-head on `rig_path` at `rate_hz` over a wire of `latency`.
Run play(const std::string& rig_path, double rate_hz, const Latency& latency, unsigned seed) {
  rig::Rig rig = config::load_rig_file(rig_path);
  rig.rate_hz = rate_hz;
  rig.links[0].baud = kBaud;
  const playback::Show show = config::load_show_file(AVAR_SOURCE_DIR "/examples/shows/hello-head.yaml");
  const assembly::Protocol& protocol = assembly::protocol_of(rig.links[0]);
  assembly::SimulatedDevice device = protocol.make_simulated(rig, 0);
  LateWire wire(*device.device, latency, seed);
  assembly::LinkEndpoint at;
  at.bytes = &wire;
  assembly::OpenedLink link = protocol.open(rig, 0, std::move(at));
  if (link.driver->start() != Status::ok) throw std::runtime_error(rig_path + ": the link did not start");
  control::ControllerOptions options;
  options.tick_period_s = 1.0 / rate_hz;
  control::Controller controller(rig, show, {link.driver.get()}, options);
  controller.begin(0, rig.rest_frame());
  Run run;
  const std::size_t n = rig.actuators.size();
  run.servo.resize(n);
  run.command.resize(n);
  // Each tick's command, by its nominal time: the reference is the motion the controller meant,
  // whenever the tick ran.
  std::vector<std::vector<double>> per_tick(n);
  const double start = wire.now_s();
  for (std::uint64_t k = 0; controller.active(); ++k) {
    const double due = start + static_cast<double>(k) / rate_hz;
    const double late = latency.tick_late(wire.rng());
    // The world up to the tick, the servos recorded on the step grid.
    while (start + static_cast<double>(run.servo[0].size() + 1) * kStepS <= due + late) {
      wire.advance_to(start + static_cast<double>(run.servo[0].size() + 1) * kStepS);
      for (std::size_t a = 0; a < n; ++a) run.servo[a].push_back(device.true_position(rig.actuators[a]));
    }
    wire.advance_to(due + late);
    controller.tick(due);
    const auto commanded = controller.commanded();
    for (std::size_t a = 0; a < n; ++a) per_tick[a].push_back(commanded[rig.actuators[a].channel.value]);
  }
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t i = 0; i < run.servo[a].size(); ++i) {
      // The motion the controller meant at step i: its ticks' commands at their nominal times,
      // joined by straight lines.
      const double ticks = static_cast<double>(i + 1) * kStepS * rate_hz;
      const auto k = static_cast<std::size_t>(std::floor(ticks));
      const std::size_t last = per_tick[a].size() - 1;
      const double from = per_tick[a][std::min(k, last)], to = per_tick[a][std::min(k + 1, last)];
      run.command[a].push_back(from + (to - from) * (ticks - static_cast<double>(k)));
    }
  run.bytes_per_s = static_cast<double>(wire.bytes_written()) / (wire.now_s() - start);
  return run;
}

struct Verdict {
  double delay_s = 0, median = 0, worst = 0;  ///< error in per cent of the channel's range
};

/// The servos against the same servos fed the commanded motion `delay` later on a perfect link:
/// the best delay (least RMS error), then the median and worst error there.
Verdict judge(const Run& run, const rig::Rig& rig) {
  Verdict best;
  double best_rms = INFINITY;
  std::vector<double> errors;
  for (int delay_ms = 0; delay_ms <= 250; ++delay_ms) {
    const auto shift = static_cast<std::size_t>(std::lround(delay_ms / 1000.0 / kStepS));
    double sum = 0;
    std::size_t count = 0;
    errors.clear();
    for (std::size_t a = 0; a < run.servo.size(); ++a) {
      const rig::ActuatorSpec& act = rig.actuators[a];
      const rig::ChannelSpec& ch = rig.channel(act.channel);
      const double range = ch.max - ch.min;
      sim::ServoModel reference(sim::ServoParams{}, act.calibration.to_device(run.command[a][0]));
      for (std::size_t i = 0; i < run.servo[a].size(); ++i) {
        const double commanded = run.command[a][i >= shift ? i - shift : 0];
        reference.step(kStepS, act.calibration.to_device(commanded));
        const double e = std::abs(run.servo[a][i] - act.calibration.to_channel(reference.position_us())) / range * 100;
        sum += e * e;
        ++count;
        errors.push_back(e);
      }
    }
    const double rms = std::sqrt(sum / static_cast<double>(count));
    if (rms < best_rms) {
      best_rms = rms;
      best.delay_s = delay_ms / 1000.0;
      std::nth_element(errors.begin(), errors.begin() + static_cast<std::ptrdiff_t>(errors.size() / 2), errors.end());
      best.median = errors[errors.size() / 2];
      best.worst = *std::max_element(errors.begin(), errors.end());
    }
  }
  return best;
}

}  // namespace

int main() try {
  const Latency latencies[] = {{"steady 1 ms", steady_delivery, on_time},
                               {"CDC-ACM jitter", cdc_delivery, cdc_tick},
                               {"FTDI latency timer, busy PC", ftdi_delivery, busy_tick}};
  const std::string maestro = AVAR_SOURCE_DIR "/examples/rigs/hello-head.yaml";
  const std::string streaming = AVAR_SOURCE_DIR "/examples/rigs/streaming-head.yaml";
  const rig::Rig rig = config::load_rig_file(maestro);
  std::printf("hello-head (8 servos, 12 s) on 115200 baud; servo error against a perfect link, %% of each channel's range\n");
  for (const Latency& latency : latencies) {
    std::printf("\n%s\n  %-37s %10s %10s %10s %10s\n", latency.name, "method", "bytes/s", "delay ms", "median %", "worst %");
    for (const double rate : {100.0, 200.0, 500.0}) {
      const Run run = play(maestro, rate, latency, 7);
      const Verdict v = judge(run, rig);
      char method[64];
      std::snprintf(method, sizeof method, "positions, Maestro at %.0f Hz", rate);
      std::printf("  %-37s %10.0f %10.0f %10.3f %10.3f\n", method, run.bytes_per_s, v.delay_s * 1000, v.median, v.worst);
    }
    const Run curve = play(streaming, 100, latency, 7);
    const Verdict v = judge(curve, rig);
    std::printf("  %-37s %10.0f %10.0f %10.3f %10.3f\n", "curves, avar-device (knots <= 50 ms)", curve.bytes_per_s,
                v.delay_s * 1000, v.median, v.worst);
  }
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "avar-bench-streaming: %s\n", e.what());
  return 1;
}
