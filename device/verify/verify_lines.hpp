#pragma once
// The lines the emulated runs print, and the hash they print of what they computed: the same text
// on every target without a library (no printf on the devices). Freestanding C++14.

#include <stdint.h>

#include "verify_run.hpp"

namespace avar {
namespace device {

// FNV-1a over bytes.
struct Hash {
  uint32_t value;
  void add(uint32_t x, unsigned bytes) {
    for (unsigned i = 0; i < bytes; ++i) {
      value ^= (x >> (8 * i)) & 0xffu;
      value *= 16777619u;
    }
  }
};

// Decimal and hexadecimal text without a library.
inline char* put_text(char* at, const char* text) {
  while (*text) *at++ = *text++;
  return at;
}
inline char* put_decimal(char* at, uint32_t v) {
  char digits[10];
  int n = 0;
  do {
    digits[n++] = static_cast<char>('0' + v % 10);
    v /= 10;
  } while (v != 0);
  while (n > 0) *at++ = digits[--n];
  return at;
}
inline char* put_hex(char* at, uint32_t v) {
  for (int i = 7; i >= 0; --i) *at++ = "0123456789abcdef"[(v >> (4 * i)) & 0xfu];
  return at;
}
inline void line(LineSink sink, const char* label, uint32_t index, uint32_t hash, uint32_t samples) {
  char text[48];
  char* at = put_text(text, label);
  at = put_decimal(at, index);
  *at++ = ' ';
  at = put_hex(at, hash);
  *at++ = ' ';
  at = put_decimal(at, samples);
  *at = 0;
  sink(text);
}

}  // namespace device
}  // namespace avar
