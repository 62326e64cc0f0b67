// avar export --verify: the exported project's figure and shows, as the board plays them, on the
// host and under the target's emulator. Every show is started by its serial command, played to
// its end and eased to rest (a looping show: twice through, then stopped); every I2C transaction
// the figure writes to its boards and every channel's 16-bit output are hashed, one line per
// second of control ticks: "show S SECOND HASH SAMPLES", then "samples N ticks T". The images are
// read in place (program memory on AVR), as on the board. Freestanding C++14.
#include "avar/device/figure.hpp"
#include "avar_shows.h"
#include "platform.hpp"
#include "verify_io.hpp"

namespace {

using namespace avar::device;

FigureStorage<AVAR_CHANNEL_COUNT, AVAR_BOARD_COUNT> storage;
Figure& figure = storage.figure;
Hash bus = {2166136261u};

constexpr FigureIo io = hashing_io(bus);

int run() {
  if (storage.open(avar_shows::kFigure, sizeof avar_shows::kFigure, avar_shows::kShows, AVAR_SHOW_COUNT) != kFigureOk ||
      figure_begin(figure, io) != kFigureOk) {
    platform_line("figure refused");
    return 1;
  }
  uint32_t samples = 0, ticks = 0;
  for (uint8_t s = 0; s < AVAR_SHOW_COUNT; ++s) {
    if (!figure_command(figure, static_cast<uint8_t>('1' + s))) {
      platform_line("show refused");
      return 1;
    }
    // Twice the show's length bounds a looping show; the ease to rest after it, 60 s.
    const uint32_t show_ticks = static_cast<uint32_t>(
        static_cast<uint64_t>(figure.player.duration) * 2u * AVAR_RATE_HZ / figure.player.ticks_per_second + AVAR_RATE_HZ);
    uint32_t second = 0, in_second = 0;
    char label[] = "show 1 ";
    label[5] = static_cast<char>('1' + s);
    Hash h = bus;
    for (uint32_t t = 0; figure.player.mode != kPlayerResting && t < show_ticks + 60u * AVAR_RATE_HZ; ++t) {
      if (t == show_ticks) figure_command(figure, 's');
      bus.value = h.value;
      figure_tick(figure, io);
      h.value = bus.value;
      for (uint8_t c = 0; c < AVAR_CHANNEL_COUNT; ++c) h.add(storage.channels[c].output, 2);
      samples += AVAR_CHANNEL_COUNT;
      ++ticks;
      if (++in_second == AVAR_RATE_HZ) {
        line(platform_line, label, second++, h.value, in_second * AVAR_CHANNEL_COUNT);
        in_second = 0;
      }
    }
    line(platform_line, "end ", s, h.value, in_second * AVAR_CHANNEL_COUNT);
    bus = h;
  }
  samples_line(platform_line, samples, ticks);
  return figure.io_fault ? 1 : 0;
}

}  // namespace

int main() { platform_exit(run()); }
