// Uses an installed avar: builds a curve from keys and evaluates it, then loads a rig and a show
// through avar::config (which links every module and their third-party libraries).
// Usage: package_consumer RIG SHOW. Prints one line per result; exits 1 on a wrong value.
#include <cmath>
#include <cstdio>
#include <exception>

#include "avar/config/rig_file.hpp"
#include "avar/config/show_file.hpp"
#include "avar/playback/runtime/curve.hpp"

namespace {

avar::playback::RawKey linear_key(double time, double value) {
  avar::playback::RawKey key;
  key.time = time;
  key.value = value;
  key.interpolation = avar::playback::Interpolation::linear;
  return key;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: package_consumer RIG SHOW\n");
    return 2;
  }
  avar::playback::RawCurve raw;
  raw.keys = {linear_key(0, 0), linear_key(2, 10)};
  const avar::playback::Curve curve = avar::playback::Curve::build(raw);
  const double mid = curve.evaluate(0.5);
  std::printf("curve(0.5) = %g\n", mid);
  if (std::abs(mid - 2.5) > 1e-12) return 1;
  try {
    const auto rig = avar::config::load_rig_file(argv[1]);
    const auto show = avar::config::load_show_file(argv[2]);
    std::printf("rig channels = %zu\nshow tracks = %zu\nshow duration = %g s\n", rig.channels.size(), show.tracks.size(),
                show.duration);
    return rig.channels.empty() || show.tracks.empty() ? 1 : 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
}
