// Writes what the WebAssembly curve engine must reproduce bit for bit (tests/tools/
// wasm_curves_test.mjs): every track of every example show and seeded random curves of every
// interpolation, easing, handle type, extrapolation and Cycles mode, each as its flat keys
// (raw_curve_codec.hpp), with sample times (keys, a microsecond either side, random times within
// and outside the keys) and the native engine's values as the bits of each double, in hex.
//
//   avar_wasm_probe OUT.json [EXAMPLES_DIR]
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "avar/config/show_file.hpp"
#include "avar/core/bit_cast.hpp"
#include "avar/core/format.hpp"
#include "avar/playback/offline/handles.hpp"
#include "avar/playback/runtime/curve.hpp"
#include "avar/playback/runtime/raw_curve_codec.hpp"

namespace {

using namespace avar::playback;

struct Probe {
  std::string name;
  RawCurve raw;
  std::string show;  ///< the example show file the track is from (a plain one, not layered); "" otherwise
  std::string channel;
  double duration = 0;
};

/// Random keys of every kind; nullopt-free: the caller keeps those that build.
RawCurve random_curve(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  const auto pick = [&](int n) { return static_cast<int>(rng() % static_cast<unsigned>(n)); };
  RawCurve raw;
  double t = -2 + 4 * u(rng);
  const int n = 1 + pick(9);
  for (int i = 0; i < n; ++i) {
    RawKey k;
    k.time = t;
    k.value = -100 + 200 * u(rng);
    k.interpolation = static_cast<Interpolation>(pick(static_cast<int>(Interpolation::bspline) + 1));
    k.easing = static_cast<Easing>(pick(4));
    k.back = 3 * u(rng);
    k.amplitude = pick(2) ? 0.0 : 80 * u(rng);
    k.period = pick(2) ? 0.0 : 0.05 + u(rng);
    k.left_type = static_cast<HandleType>(pick(5));
    k.right_type = static_cast<HandleType>(pick(5));
    // Free and aligned sides need their handle; others may have one too (ignored or used).
    k.left = Handle{t - 0.6 * u(rng), k.value - 60 + 120 * u(rng)};
    k.right = Handle{t + 0.6 * u(rng), k.value - 60 + 120 * u(rng)};
    if (pick(3) == 0) k.in_slope = -80 + 160 * u(rng);
    if (pick(3) == 0) k.out_slope = -80 + 160 * u(rng);
    k.tension = -1 + 2 * u(rng);
    k.continuity = -1 + 2 * u(rng);
    k.bias = -1 + 2 * u(rng);
    raw.keys.push_back(k);
    t += 0.01 + 1.5 * u(rng);
  }
  raw.extrapolation = static_cast<Extrapolation>(pick(2));
  raw.auto_smoothing = static_cast<AutoSmoothing>(pick(2));
  raw.cycles.before = static_cast<CycleMode>(pick(4));
  raw.cycles.after = static_cast<CycleMode>(pick(4));
  raw.cycles.before_count = pick(3);
  raw.cycles.after_count = pick(3);
  return raw;
}

std::vector<double> sample_times(const RawCurve& raw, std::mt19937_64& rng) {
  std::vector<double> times;
  for (const RawKey& k : raw.keys) times.insert(times.end(), {k.time, k.time - 1e-6, k.time + 1e-6, k.time + 5e-7});
  const double first = raw.keys.front().time, last = raw.keys.back().time;
  std::uniform_real_distribution<double> within(first - 0.5 * (last - first) - 1, last + 0.5 * (last - first) + 1);
  while (times.size() < 60) times.push_back(within(rng));
  return times;
}

std::string hex_bits(double v) {
  char buf[20];
  std::snprintf(buf, sizeof buf, "%016" PRIx64, avar::bit_cast<std::uint64_t>(v));
  return buf;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: avar_wasm_probe OUT.json [EXAMPLES_DIR]\n";
    return 2;
  }
  std::vector<Probe> probes;
  if (argc > 2)
    for (const auto& entry : std::filesystem::directory_iterator(argv[2])) {
      if (entry.path().extension() != ".yaml") continue;
      try {
        const Show show = avar::config::load_show_file(entry.path().string());
        // `avar sample` prints a plain show's tracks as they are; a layered one composed.
        const std::string plain = show.layered() ? "" : entry.path().string();
        for (const Track& track : show.tracks)
          probes.push_back(
              {entry.path().filename().string() + ":" + track.channel, track.raw, plain, track.channel, show.duration});
      } catch (const std::exception& e) {
        std::cerr << "skipped " << entry.path() << ": " << e.what() << '\n';
      }
    }
  std::mt19937_64 rng(20261206);
  for (int made = 0; made < 400;) {
    RawCurve raw = random_curve(rng);
    try {
      (void)Curve::build(raw);
    } catch (const std::exception&) {
      continue;  // keys the builder refuses: not a curve to compare
    }
    probes.push_back({"random " + std::to_string(made++), std::move(raw), "", "", 0});
  }
  std::ofstream out(argv[1]);
  std::size_t samples = 0;
  out << "{\"curves\": [\n";
  for (std::size_t i = 0; i < probes.size(); ++i) {
    const Curve curve = Curve::build(probes[i].raw);
    const std::vector<double> times = sample_times(probes[i].raw, rng);
    std::string flat, at, bits;
    for (double v : encode_raw_curve(probes[i].raw)) avar::append_round_trip(flat += flat.empty() ? "" : ",", v);
    for (double t : times) {
      avar::append_round_trip(at += at.empty() ? "" : ",", t);
      bits += (bits.empty() ? "\"" : ",\"") + hex_bits(curve.evaluate(t)) + "\"";
    }
    samples += times.size();
    // Every key's handles as the engine computes them (left time, value, right time, value; NaN
    // for a side without one), for the page's graph editor.
    std::string handles;
    const auto side = [&](const std::optional<avar::playback::Handle>& h) {
      for (double v : {h ? h->time : std::nan(""), h ? h->value : std::nan("")})
        handles += (handles.empty() ? "\"" : ",\"") + hex_bits(v) + "\"";
    };
    for (const avar::playback::ResolvedHandles& h : avar::playback::compute_handles(probes[i].raw)) {
      side(h.left);
      side(h.right);
    }
    out << "{\"name\": \"" << probes[i].name << "\", \"flat\": [" << flat << "], \"times\": [" << at << "], \"bits\": [" << bits
        << "], \"handles\": [" << handles << "], \"show\": \"" << probes[i].show << "\", \"channel\": \"" << probes[i].channel
        << "\", \"duration\": " << probes[i].duration << "}" << (i + 1 < probes.size() ? ",\n" : "\n");
  }
  out << "]}\n";
  std::cout << "avar_wasm_probe: " << probes.size() << " curves, " << samples << " samples -> " << argv[1] << '\n';
  return out ? 0 : 1;
}
