// The verification run on an AVR under simavr (platform_avr.cpp): the golden image in program
// memory, copied to RAM (the run reads its images with plain loads).
#include <avr/pgmspace.h>

#define kGoldenImage kGoldenImageFlash
#define AVAR_GOLDEN_IMAGE_ATTRIBUTE PROGMEM
#include "golden_image.inc"
#undef kGoldenImage
#include "platform.hpp"
#include "verify_main.hpp"

namespace {

uint8_t golden[sizeof kGoldenImageFlash];

}  // namespace

int main() {
  for (uint16_t i = 0; i < sizeof golden; ++i) golden[i] = pgm_read_byte(&kGoldenImageFlash[i]);
  avar::device::run_verification(golden, sizeof golden, platform_line);
  platform_exit(0);
}
