#pragma once
// The device engine's bit-identity run: the same source built for the host and for each emulated
// target (simavr, QEMU) samples the golden image and a seeded family of random images, and prints
// one line per channel or batch with a hash of every sample; a test compares the targets' lines
// with the host's (tests/tools/device_verify.py). Freestanding C++14, integer only.

#include <stdint.h>

namespace avar {
namespace device {

/// Where the run's lines go: the platform's console (stdout, a UART, semihosting). Each call is
/// one line without its newline.
typedef void (*LineSink)(const char* line);

struct VerifyCounts {
  uint32_t samples;
  uint32_t invalid;     ///< random images check_image refused (the generator's own bug: must be 0)
  uint32_t violations;  ///< player ticks over a speed, acceleration or range limit: must be 0
};

/// Samples every channel of `image` (in RAM) every `step` ticks from two seconds before its
/// first key to two seconds after its last; one line per channel: "golden C HASH SAMPLES".
void verify_image(const uint8_t* image, uint32_t size, int32_t step, LineSink sink, VerifyCounts& counts);

/// `curves` random one-channel images from `seed` (every segment kind, easing, extrapolation and
/// Cycles mode, parameters across the engine's bounds), each sampled at 8 random ticks; one line
/// per 1000 curves: "random B HASH SAMPLES".
void verify_random(uint32_t seed, uint32_t curves, LineSink sink, VerifyCounts& counts);

/// The player on `switches` seeded switches: 4 random one-channel shows and a stop, one of them
/// every 1 to 30 control ticks, mid-motion, through random limits; every tick's position, speed
/// and speed change checked against the limits on the device itself. One line:
/// "player SWITCHES HASH TICKS" and the count of ticks over a limit in counts.violations.
void verify_player(uint32_t seed, uint32_t switches, LineSink sink, VerifyCounts& counts);

/// The closing line: "samples N invalid M violations V".
void verify_summary(const VerifyCounts& counts, LineSink sink);

}  // namespace device
}  // namespace avar
