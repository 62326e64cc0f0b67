// avar-bench-device: the device engine on the host. First a table of show image sizes, bytes per
// key on the bundled shows (beside Bottango's 34 to 45 bytes of command text per Bezier segment,
// its published export format); then the cost of one channel sample on a long curve sampled at
// a 1 kHz tick, for each kind of segment, beside avar's double engine on the same curve (the
// reference the device engine follows). Cycles on a microcontroller are measured under simavr
// by the export's own benchmark; these are host nanoseconds (one iteration is one sample).
#include <benchmark/benchmark.h>

#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "avar/config/rig_file.hpp"
#include "avar/config/show_file.hpp"
#include "avar/device/image_sampler.hpp"
#include "avar/device/show_export.hpp"
#include "avar/playback/runtime/curve.hpp"

namespace {

using avar::playback::Curve;
using avar::playback::Interpolation;
using avar::playback::RawCurve;
using avar::playback::RawKey;

void print_sizes() {
  struct Example {
    const char* show;
    const char* rig;
  };
  const Example examples[] = {{"examples/shows/hello-head.yaml", "examples/rigs/hello-head.yaml"},
                              {"examples/shows/mixed-figure.yaml", "examples/rigs/mixed-figure.yaml"},
                              {"examples/shows/haunt-prop.yaml", "examples/rigs/haunt-prop.yaml"},
                              {"tests/playback/golden/blender_curves.yaml", nullptr}};
  std::printf("%-44s %6s %8s %10s %10s %9s\n", "show image", "keys", "bezier", "key bytes", "bytes/key", "image");
  for (const Example& e : examples) {
    const avar::playback::Show show = avar::config::load_show_file(std::string(AVAR_SOURCE_DIR "/") + e.show);
    std::vector<avar::device::ImageChannel> channels;
    for (const auto& t : show.tracks) {
      avar::device::OutputRange range{-100, 100};
      if (e.rig) {
        const avar::rig::Rig rig = avar::config::load_rig_file(std::string(AVAR_SOURCE_DIR "/") + e.rig);
        const auto& c = rig.channels[rig.find_channel(t.channel).value()];
        range = {c.min, c.max};
      }
      channels.push_back({t.channel, range});
    }
    const avar::device::ShowImage image = avar::device::encode_show_image(show, channels);
    std::printf("%-44s %6zu %8zu %10zu %10.2f %9zu\n", e.show, image.keys, image.bezier_keys, image.key_bytes,
                static_cast<double>(image.key_bytes) / static_cast<double>(image.keys), image.bytes.size());
  }
  std::printf("(bezier: keys whose Bezier segment is solved in time; Bottango: 34-45 bytes per Bezier segment)\n\n");
}

enum Kind { kLinear, kStep, kBezierThirds, kBezierFree, kSine };

// A 10-minute curve of about a thousand keys on a 1 ms grid.
RawCurve long_raw(Kind kind) {
  std::mt19937 rng(20261207);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<RawKey> keys;
  for (int ms = 0; ms <= 600000; ms += 200 + static_cast<int>(rng() % 800)) {
    RawKey k;
    k.time = ms / 1000.0;
    k.value = -90 + 180 * u(rng);
    k.interpolation = kind == kLinear ? Interpolation::linear
                      : kind == kStep ? Interpolation::step
                      : kind == kSine ? Interpolation::sine
                                      : Interpolation::bezier;
    keys.push_back(k);
  }
  for (std::size_t i = 0; i < keys.size() && (kind == kBezierThirds || kind == kBezierFree); ++i) {
    const double before = i > 0 ? keys[i].time - keys[i - 1].time : 0.5,
                 after = i + 1 < keys.size() ? keys[i + 1].time - keys[i].time : 0.5;
    const double slope = -100 + 200 * u(rng);
    const double l = kind == kBezierThirds ? before / 3 : (0.1 + 0.5 * u(rng)) * before;
    const double r = kind == kBezierThirds ? after / 3 : (0.1 + 0.5 * u(rng)) * after;
    keys[i].left = avar::playback::Handle{keys[i].time - l, keys[i].value - slope * l};
    keys[i].right = avar::playback::Handle{keys[i].time + r, keys[i].value + slope * r};
  }
  return RawCurve(std::move(keys), {});
}

void run(benchmark::State& state, Kind kind, bool device) {
  const RawCurve raw = long_raw(kind);
  const Curve curve = Curve::build(raw);
  const std::uint32_t tps = 1000;
  avar::device::ImageSampler sampler(
      avar::device::single_channel_image(avar::device::encode_channel_record(raw, curve, {-200, 200}, tps), tps, 600000));
  avar::playback::CurveCursor cursor;
  std::int32_t tick = 0;
  double sum = 0;
  for (auto _ : state) {
    if (device) {
      sum += sampler.output(0, tick);
    } else {
      sum += curve.evaluate(tick / 1000.0, cursor);
    }
    tick = tick == 600000 ? 0 : tick + 1;
  }
  benchmark::DoNotOptimize(sum);
}

void register_all() {
  const std::pair<const char*, Kind> kinds[] = {
      {"linear", kLinear}, {"step", kStep}, {"bezier_thirds", kBezierThirds}, {"bezier_free", kBezierFree}, {"sine", kSine}};
  for (const auto& [name, kind] : kinds) {
    const Kind k = kind;
    benchmark::RegisterBenchmark((std::string("DeviceEngine/") + name).c_str(), [k](benchmark::State& s) { run(s, k, true); });
    benchmark::RegisterBenchmark((std::string("DoubleEngine/") + name).c_str(), [k](benchmark::State& s) { run(s, k, false); });
  }
}

}  // namespace

int main(int argc, char** argv) {
  print_sizes();
  register_all();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
