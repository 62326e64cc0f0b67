// avar-bench-sync: several controllers chasing one timecode source, in step. For each source,
// two controllers at 100 Hz run the same chase code as `avar play --timecode` (ChaseClock over a
// TimecodeSource, the real decoders), each on its own copy of the signal, for 60 s of simulated
// time; controller B ticks 3.7 ms after controller A (never in step). Measured per tick of A:
//   diff:  |show time of A - show time of B at the same instant| (B interpolated between its
//          ticks), in ticks (10 ms);
//   chase: |chase clock - the true source time| at that instant, ms (both controllers).
// The sources:
//   ltc    LTC audio encoded by libltc (25 fps, 48 kHz), decoded by each controller with
//          libltc as an audio input delivers it: 256-sample periods, stamps from the sample
//          clock running 50 ppm fast against the machine's, 0-100 µs timestamp jitter (seeded);
//   mtc    a MIDI Time Code byte stream (quarter frames every 10 ms at 25 fps), each message
//          reaching each controller late by an independent 0-1 ms (USB MIDI scheduling; seeded);
//   artnet ArtTimeCode packets at 25 fps through the codec, each late by an independent 0-200 µs
//          (loopback network and scheduling; seeded).
// The decoders run ahead in arrival order (they are pure state machines); the chase replays
// their positions on the stepped clock. The two-process test (tests/apps/timecode_play_test.cpp) measures the same on real UDP.
// Prints one line per source:
//   sync,source=<ltc|mtc|artnet>,controllers=2,rate_hz=100,p99_diff_ticks=<x>,chase_p99_ms=<y>
// and the medians and maxima on the error stream.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "avar/control/chase_clock.hpp"
#include "avar/inputs/artnet_timecode_codec.hpp"
#include "avar/inputs/ltc_audio.hpp"
#include "avar/inputs/ltc_decoder.hpp"
#include "avar/inputs/mtc_decoder.hpp"

namespace {

using namespace avar;

constexpr double kRateHz = 100;
constexpr double kDt = 1.0 / kRateHz;
constexpr double kSeconds = 60;
constexpr double kPhaseB = 0.0037;
constexpr double kStart = 3600;  // the source starts at 01:00:00:00

/// Positions as the real decoders made them from the signal, each visible to the controller from
/// `visible_s` on, stamped `stamp_s` (the receiver's arrival stamp); replayed on the stepped clock.
struct ArrivingFix {
  double visible_s;
  double stamp_s;
  inputs::TimecodeFix fix;
};

class ArrivingFixes final : public inputs::TimecodeSource {
 public:
  explicit ArrivingFixes(std::vector<ArrivingFix> fixes) : fixes_(std::move(fixes)) {}
  void start() override {}
  void stop() noexcept override {}
  inputs::TimecodeReading latest() const noexcept override { return mailbox_.read(); }
  inputs::TimecodeCounters counters() const noexcept override { return {}; }
  std::string describe() const override { return "simulated"; }
  bool stepped() const noexcept override { return true; }
  void advance_to(std::int64_t now_ns) noexcept override {
    const double now = static_cast<double>(now_ns) * 1e-9;
    for (; next_ < fixes_.size() && fixes_[next_].visible_s <= now; ++next_)
      mailbox_.publish(fixes_[next_].fix, static_cast<std::int64_t>(std::llround(fixes_[next_].stamp_s * 1e9)));
  }

 private:
  std::vector<ArrivingFix> fixes_;  ///< by visible_s
  std::size_t next_ = 0;
  inputs::TimecodeMailbox mailbox_;
};

struct SyncFigures {
  std::vector<double> diff_ticks;
  std::vector<double> chase_ms;
};

double sync_percentile(std::vector<double> v, double f) {
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(f * static_cast<double>(v.size())))];
}

/// Runs controllers A and B over their sources; the true source time at t is kStart + speed * t.
SyncFigures run_pair(inputs::TimecodeSource& a, inputs::TimecodeSource& b, double speed = 1.0) {
  control::ChaseOptions o;
  o.offset_s = kStart;
  control::ChaseClock chase_a(a, o, nullptr), chase_b(b, o, nullptr);
  SyncFigures f;
  double b_prev_t = -1, b_prev_show = 0;
  const auto ticks = static_cast<int>(kSeconds * kRateHz);
  for (int k = 0; k < ticks; ++k) {
    const double ta = k * kDt, tb = ta + kPhaseB;
    const double show_a = chase_a.read(ta).show_time_s;
    const bool a_locked = chase_a.state() == control::ChaseState::locked;
    const double chase_a_s = chase_a.chase_time_s();
    const double show_b = chase_b.read(tb).show_time_s;
    const bool b_locked = chase_b.state() == control::ChaseState::locked;
    // Skip the first second (lock-in).
    if (ta > 1.0 && a_locked && b_locked && b_prev_t >= 0) {
      const double b_at_a = b_prev_show + (show_b - b_prev_show) * (ta - b_prev_t) / (tb - b_prev_t);
      f.diff_ticks.push_back(std::abs(show_a - b_at_a) / kDt);
      f.chase_ms.push_back(std::abs(chase_a_s - (kStart + speed * ta)) * 1e3);
      f.chase_ms.push_back(std::abs(chase_b.chase_time_s() - (kStart + speed * tb)) * 1e3);
    }
    b_prev_t = tb;
    b_prev_show = show_b;
  }
  return f;
}

void report(const char* source, const SyncFigures& f) {
  std::printf("sync,source=%s,controllers=2,rate_hz=%g,p99_diff_ticks=%.4f,chase_p99_ms=%.4f\n", source, kRateHz,
              sync_percentile(f.diff_ticks, 0.99), sync_percentile(f.chase_ms, 0.99));
  std::fprintf(stderr, "  %s: %zu ticks; diff (ticks) p50 %.4f max %.4f; chase (ms) p50 %.4f max %.4f\n", source,
               f.diff_ticks.size(), sync_percentile(f.diff_ticks, 0.5), sync_percentile(f.diff_ticks, 1.0),
               sync_percentile(f.chase_ms, 0.5), sync_percentile(f.chase_ms, 1.0));
}

/// Each controller decodes the LTC audio with LtcDecoder as an audio input delivers it: periods
/// of 256 samples (a position is visible when its period is), stamped from the sample clock, which
/// runs 50 ppm fast against the machine's, with 0-100 µs of timestamp jitter.
std::vector<ArrivingFix> ltc_arrivals(const std::vector<float>& audio, std::mt19937_64& rng) {
  constexpr double kSampleRate = 48000, kSkew = 1.0 + 50e-6;
  std::uniform_real_distribution<double> jitter(0, 100e-6);
  inputs::LtcDecoder decoder(kSampleRate);
  std::vector<ArrivingFix> out;
  for (std::size_t at = 0; at < audio.size(); at += 256) {
    const std::size_t n = std::min<std::size_t>(256, audio.size() - at);
    const double visible = static_cast<double>(at + n) / kSampleRate / kSkew;
    decoder.feed(std::span(audio.data() + at, n), [&](const inputs::TimecodeFix& fix, std::int64_t end) {
      out.push_back({visible, static_cast<double>(end + 1) / kSampleRate / kSkew + jitter(rng), fix});
    });
  }
  return out;
}

SyncFigures bench_ltc() {
  const auto frames = static_cast<std::size_t>((kSeconds + 1) * 25);
  const std::vector<float> audio = inputs::encode_ltc_audio(Timecode{1, 0, 0, 0, FrameRate::fps25}, frames, 48000);
  std::mt19937_64 rng(5);
  ArrivingFixes a(ltc_arrivals(audio, rng)), b(ltc_arrivals(audio, rng));
  // The sample clock is the source's: 50 ppm fast against the machine.
  return run_pair(a, b, 1.0 + 50e-6);
}

/// The messages decoded in arrival order by `decode`, each late by an independent 0..jitter_s.
template <class Decode>
std::vector<ArrivingFix> message_arrivals(const std::vector<std::pair<double, std::vector<std::uint8_t>>>& sent, double jitter_s,
                                          std::mt19937_64& rng, Decode decode) {
  std::uniform_real_distribution<double> late(0, jitter_s);
  std::vector<ArrivingFix> out;
  double previous = 0;
  for (const auto& [when, bytes] : sent) {
    // A message cannot overtake the one before it on one wire.
    const double arrival = std::max(previous, when + late(rng));
    previous = arrival;
    inputs::TimecodeFix fix;
    if (decode(bytes, fix)) out.push_back({arrival, arrival, fix});
  }
  return out;
}

SyncFigures bench_mtc() {
  // Quarter frame q goes out at q * 10 ms; its sequence names frame 2 * (q / 8).
  std::vector<std::pair<double, std::vector<std::uint8_t>>> sent;
  const auto quarters = static_cast<int>((kSeconds + 1) * 100);
  const std::int64_t first = to_frame_number(Timecode{1, 0, 0, 0, FrameRate::fps25});
  for (int q = 0; q < quarters; ++q) {
    const Timecode t = from_frame_number(first + 2 * (q / 8), FrameRate::fps25);
    const int piece = q % 8;
    const int fields[8] = {t.frames & 0xF,  t.frames >> 4,  t.seconds & 0xF, t.seconds >> 4,
                           t.minutes & 0xF, t.minutes >> 4, t.hours & 0xF,   (t.hours >> 4) | (1 << 1)};
    sent.push_back({q * 0.01, {0xF1, static_cast<std::uint8_t>((piece << 4) | fields[piece])}});
  }
  std::mt19937_64 rng(7);
  const auto decoder = [] {
    return [d = std::make_shared<inputs::MtcDecoder>()](const std::vector<std::uint8_t>& m, inputs::TimecodeFix& fix) {
      return d->decode(m, fix) == inputs::MtcVerdict::fix;
    };
  };
  ArrivingFixes a(message_arrivals(sent, 0.001, rng, decoder())), b(message_arrivals(sent, 0.001, rng, decoder()));
  return run_pair(a, b);
}

SyncFigures bench_artnet() {
  std::vector<std::pair<double, std::vector<std::uint8_t>>> sent;
  const std::int64_t first = to_frame_number(Timecode{1, 0, 0, 0, FrameRate::fps25});
  for (int f = 0; f < static_cast<int>((kSeconds + 1) * 25); ++f) {
    std::vector<std::uint8_t> packet(inputs::artnet::kTimeCodeSize);
    (void)inputs::artnet::encode_timecode(from_frame_number(first + f, FrameRate::fps25), 0, packet);
    sent.push_back({f * 0.04, std::move(packet)});
  }
  std::mt19937_64 rng(11);
  const auto decode = [](const std::vector<std::uint8_t>& m, inputs::TimecodeFix& fix) {
    Timecode t;
    if (inputs::artnet::decode_timecode(m, t) != inputs::artnet::TimeCodeVerdict::ok) return false;
    fix = inputs::TimecodeFix{t, 0.0, false};
    return true;
  };
  ArrivingFixes a(message_arrivals(sent, 0.0002, rng, decode)), b(message_arrivals(sent, 0.0002, rng, decode));
  return run_pair(a, b);
}

}  // namespace

int main() {
  std::fprintf(stderr, "avar-bench-sync: 2 controllers at 100 Hz, 60 s simulated per source (seeds 5, 7, 11)\n");
  report("ltc", bench_ltc());
  report("mtc", bench_mtc());
  report("artnet", bench_artnet());
  return 0;
}
