// The AVR cycle benchmark's firmware (bench/avr): every channel of the image (in program memory,
// read in place as an exported show is) sampled at 200 Hz from one second before its first key
// to one second after its last, each sample timed by Timer1 at the CPU clock; one line per
// channel: "cycles NAME SAMPLES MEAN MAX", the timing's own overhead taken off. Built for the
// ATmega328P with the lean image and the features an Uno export of it has, and for the ATmega2560
// with every feature (AVAR_CYCLES_IMAGE: Lean or Full).
#include <avr/io.h>

#include "avar/device/curve_engine.hpp"
#include "cycles_images.inc"
#include "platform.hpp"
#include "verify_lines.hpp"

#define AVAR_JOIN(a, b, c) a##b##c
#define AVAR_IMAGE(name) AVAR_JOIN(k, name, Image)
#define AVAR_NAMES(name) AVAR_JOIN(k, name, Names)

namespace {

using namespace avar::device;

volatile uint16_t sink_value;

// Cycles of one call of `f` by Timer1 (clk/1), with one overflow of the 16-bit counter counted.
template <typename F>
uint32_t timed(F f) {
  TCCR1A = 0;
  TCCR1B = 0;
  TCNT1 = 0;
  TIFR1 = (1 << TOV1);
  TCCR1B = (1 << CS10);
  f();
  const uint16_t counted = TCNT1;  // read running (simavr updates a stopped counter lazily)
  const bool overflowed = (TIFR1 & (1 << TOV1)) != 0;
  TCCR1B = 0;
  return counted + (overflowed ? 65536u : 0u);
}

}  // namespace

int main() {
  const uint8_t* image = AVAR_IMAGE(AVAR_CYCLES_IMAGE);
  const uint32_t size = sizeof AVAR_IMAGE(AVAR_CYCLES_IMAGE);
  ShowHeader header;
  if (check_image(image, size, header) != kImageOk) {
    platform_line("image refused");
    platform_exit(1);
  }
  const uint32_t overhead = timed([] { sink_value = 0; });
  for (uint8_t c = 0; c < header.channel_count; ++c) {
    Channel ch;
    SegmentCache cache;
    open_channel(image, size, c, ch);
    reset_cache(cache);
    const int32_t step = static_cast<int32_t>(header.ticks_per_second / 200);
    uint32_t samples = 0, total = 0, worst = 0;
    for (int32_t t = ch.start - static_cast<int32_t>(header.ticks_per_second);
         t <= ch.end + static_cast<int32_t>(header.ticks_per_second); t += step) {
      const uint32_t cycles = timed([&] { sink_value = sample(ch, cache, t); }) - overhead;
      total += cycles;
      if (cycles > worst) worst = cycles;
      ++samples;
    }
    char text[64];
    char* at = put_text(text, "cycles ");
    at = put_text(at, AVAR_NAMES(AVAR_CYCLES_IMAGE)[c]);
    *at++ = ' ';
    at = put_decimal(at, samples);
    *at++ = ' ';
    at = put_decimal(at, (total + samples / 2) / samples);
    *at++ = ' ';
    at = put_decimal(at, worst);
    *at = 0;
    platform_line(text);
  }
  platform_exit(0);
}
