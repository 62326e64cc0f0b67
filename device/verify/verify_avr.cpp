// The verification run on an AVR (ATmega2560 under simavr): lines on UART0, which simavr prints;
// the golden image in program memory, copied to RAM; at the end the CPU sleeps with interrupts
// off, which ends simavr.
#include <avr/interrupt.h>
#include <avr/io.h>
#include <avr/pgmspace.h>
#include <avr/sleep.h>

#define kGoldenImage kGoldenImageFlash
#define AVAR_GOLDEN_IMAGE_ATTRIBUTE PROGMEM
#include "golden_image.inc"
#undef kGoldenImage
#include "verify_main.hpp"

namespace {

uint8_t golden[sizeof kGoldenImageFlash];

void put(char c) {
  while (!(UCSR0A & (1 << UDRE0))) {
  }
  UDR0 = static_cast<uint8_t>(c);
}

void sink(const char* line) {
  while (*line) put(*line++);
  put('\n');
}

}  // namespace

int main() {
  UBRR0 = 8;  // 115200 baud at 16 MHz
  UCSR0B = (1 << TXEN0);
  for (uint16_t i = 0; i < sizeof golden; ++i) golden[i] = pgm_read_byte(&kGoldenImageFlash[i]);
  avar::device::run_verification(golden, sizeof golden, sink);
  UCSR0A = (1 << TXC0);
  while (!(UCSR0A & (1 << TXC0))) {
  }
  set_sleep_mode(SLEEP_MODE_PWR_DOWN);
  sleep_enable();
  cli();
  sleep_cpu();
  for (;;) {
  }
}
