// A Cortex-M board under QEMU (lm3s6965evb: Cortex-M3; microbit: Cortex-M0; mps2-an386:
// Cortex-M4): lines through semihosting, then a semihosting exit that ends QEMU. No C library:
// the vector table, the reset handler and the few memory functions the compiler may call are
// here (cortex_m.ld places them).
#include <stddef.h>
#include <stdint.h>

#include "platform.hpp"

int main();

extern "C" {
extern uint32_t __data_load, __data_start, __data_end, __bss_start, __bss_end, __stack_top;

void* memcpy(void* to, const void* from, size_t n) {
  auto* d = static_cast<uint8_t*>(to);
  const auto* s = static_cast<const uint8_t*>(from);
  while (n--) *d++ = *s++;
  return to;
}
void* memset(void* to, int value, size_t n) {
  auto* d = static_cast<uint8_t*>(to);
  while (n--) *d++ = static_cast<uint8_t>(value);
  return to;
}
void* memmove(void* to, const void* from, size_t n) {
  auto* d = static_cast<uint8_t*>(to);
  const auto* s = static_cast<const uint8_t*>(from);
  if (d < s) {
    while (n--) *d++ = *s++;
  } else {
    while (n--) d[n] = s[n];
  }
  return to;
}
}

namespace {

// ARM semihosting: r0 the operation, r1 its argument, bkpt 0xab.
uint32_t semihost(uint32_t operation, const void* argument) {
  register uint32_t r0 __asm__("r0") = operation;
  register const void* r1 __asm__("r1") = argument;
  __asm__ volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
  return r0;
}

}  // namespace

void platform_line(const char* line) {
  semihost(0x04, line);  // SYS_WRITE0
  semihost(0x04, "\n");
}

void platform_exit(int status) {
  // SYS_EXIT: ADP_Stopped_ApplicationExit, or ADP_Stopped_RunTimeErrorUnknown on a failure.
  semihost(0x18, reinterpret_cast<const void*>(static_cast<uintptr_t>(status == 0 ? 0x20026 : 0x20023)));
  for (;;) {
  }
}

extern "C" [[noreturn]] void reset_handler() {
  uint32_t* from = &__data_load;
  for (uint32_t* to = &__data_start; to < &__data_end;) *to++ = *from++;
  for (uint32_t* to = &__bss_start; to < &__bss_end;) *to++ = 0;
  platform_exit(main());
}

extern "C" void fault_handler() {
  platform_line("fault");
  platform_exit(1);
}

// The vector table: the stack's top, then reset, NMI and hard fault.
__attribute__((section(".vectors"), used)) void (*const kVectors[4])() = {reinterpret_cast<void (*)()>(&__stack_top),
                                                                          reset_handler, fault_handler, fault_handler};
