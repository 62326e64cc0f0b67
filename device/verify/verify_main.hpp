#pragma once
// What every build of the verification run does, in order, on its platform's line sink: the
// golden image (golden_image.inc, generated from tests/playback/golden at build time), then
// AVAR_VERIFY_CURVES random images from AVAR_VERIFY_SEED, the player through AVAR_VERIFY_SWITCHES
// switches, then the summary.

#include "verify_run.hpp"

#ifndef AVAR_VERIFY_SEED
#define AVAR_VERIFY_SEED 20261207u
#endif
#ifndef AVAR_VERIFY_CURVES
#define AVAR_VERIFY_CURVES 100000u
#endif
#ifndef AVAR_VERIFY_SWITCHES
#define AVAR_VERIFY_SWITCHES 10000u
#endif

namespace avar {
namespace device {

/// The golden image's samples are AVAR_VERIFY_GOLDEN_STEP ticks apart (24 kHz ticks: 100 Hz).
#ifndef AVAR_VERIFY_GOLDEN_STEP
#define AVAR_VERIFY_GOLDEN_STEP 240
#endif

inline void run_verification(const uint8_t* golden, uint32_t golden_size, LineSink sink) {
  VerifyCounts counts = {0, 0, 0};
  verify_image(golden, golden_size, AVAR_VERIFY_GOLDEN_STEP, sink, counts);
  verify_random(AVAR_VERIFY_SEED, AVAR_VERIFY_CURVES, sink, counts);
  verify_player(AVAR_VERIFY_SEED + 1, AVAR_VERIFY_SWITCHES, sink, counts);
  verify_summary(counts, sink);
}

}  // namespace device
}  // namespace avar
