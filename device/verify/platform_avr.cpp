// An AVR under simavr (16 MHz): lines on UART0, which simavr prints; at the end the CPU sleeps
// with interrupts off, which ends simavr.
#include <avr/interrupt.h>
#include <avr/io.h>
#include <avr/sleep.h>

#include "platform.hpp"

namespace {

void put(char c) {
  if (!(UCSR0B & (1 << TXEN0))) {
    UBRR0 = 8;  // 115200 baud at 16 MHz
    UCSR0B = (1 << TXEN0);
  }
  while (!(UCSR0A & (1 << UDRE0))) {
  }
  UDR0 = static_cast<uint8_t>(c);
}

}  // namespace

void platform_line(const char* line) {
  while (*line) put(*line++);
  put('\n');
}

void platform_exit(int) {
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
