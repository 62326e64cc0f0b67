#include "avar/device/fixed_math.hpp"

namespace avar {
namespace device {

int64_t shift_floor(int64_t x, unsigned n) {
  if (x >= 0) return static_cast<int64_t>(static_cast<uint64_t>(x) >> n);
  return -static_cast<int64_t>((static_cast<uint64_t>(-(x + 1)) >> n)) - 1;
}

int64_t mul_q30(int64_t a, int64_t b) { return shift_floor(a * b, 30); }

WideProduct mul_wide(uint32_t a, uint32_t b) {
  WideProduct p;
#if defined(__AVR__) && defined(__AVR_HAVE_MUL__)
  uint8_t zero;
  __asm__(
      "clr %[z]\n\t"
      // the diagonal: a0 b0, a1 b1, a2 b2, a3 b3 at bytes 0, 2, 4, 6
      "mul %A[a],%A[b]\n\tmovw %A[lo],r0\n\t"
      "mul %B[a],%B[b]\n\tmovw %C[lo],r0\n\t"
      "mul %C[a],%C[b]\n\tmovw %A[hi],r0\n\t"
      "mul %D[a],%D[b]\n\tmovw %C[hi],r0\n\t"
      // byte 1: a0 b1, a1 b0
      "mul %A[a],%B[b]\n\tadd %B[lo],r0\n\tadc %C[lo],r1\n\tadc %D[lo],%[z]\n\tadc %A[hi],%[z]\n\tadc %B[hi],%[z]\n\tadc "
      "%C[hi],%[z]\n\tadc %D[hi],%[z]\n\t"
      "mul %B[a],%A[b]\n\tadd %B[lo],r0\n\tadc %C[lo],r1\n\tadc %D[lo],%[z]\n\tadc %A[hi],%[z]\n\tadc %B[hi],%[z]\n\tadc "
      "%C[hi],%[z]\n\tadc %D[hi],%[z]\n\t"
      // byte 2: a0 b2, a2 b0
      "mul %A[a],%C[b]\n\tadd %C[lo],r0\n\tadc %D[lo],r1\n\tadc %A[hi],%[z]\n\tadc %B[hi],%[z]\n\tadc %C[hi],%[z]\n\tadc "
      "%D[hi],%[z]\n\t"
      "mul %C[a],%A[b]\n\tadd %C[lo],r0\n\tadc %D[lo],r1\n\tadc %A[hi],%[z]\n\tadc %B[hi],%[z]\n\tadc %C[hi],%[z]\n\tadc "
      "%D[hi],%[z]\n\t"
      // byte 3: a0 b3, a3 b0, a1 b2, a2 b1
      "mul %A[a],%D[b]\n\tadd %D[lo],r0\n\tadc %A[hi],r1\n\tadc %B[hi],%[z]\n\tadc %C[hi],%[z]\n\tadc %D[hi],%[z]\n\t"
      "mul %D[a],%A[b]\n\tadd %D[lo],r0\n\tadc %A[hi],r1\n\tadc %B[hi],%[z]\n\tadc %C[hi],%[z]\n\tadc %D[hi],%[z]\n\t"
      "mul %B[a],%C[b]\n\tadd %D[lo],r0\n\tadc %A[hi],r1\n\tadc %B[hi],%[z]\n\tadc %C[hi],%[z]\n\tadc %D[hi],%[z]\n\t"
      "mul %C[a],%B[b]\n\tadd %D[lo],r0\n\tadc %A[hi],r1\n\tadc %B[hi],%[z]\n\tadc %C[hi],%[z]\n\tadc %D[hi],%[z]\n\t"
      // byte 4: a1 b3, a3 b1
      "mul %B[a],%D[b]\n\tadd %A[hi],r0\n\tadc %B[hi],r1\n\tadc %C[hi],%[z]\n\tadc %D[hi],%[z]\n\t"
      "mul %D[a],%B[b]\n\tadd %A[hi],r0\n\tadc %B[hi],r1\n\tadc %C[hi],%[z]\n\tadc %D[hi],%[z]\n\t"
      // byte 5: a2 b3, a3 b2
      "mul %C[a],%D[b]\n\tadd %B[hi],r0\n\tadc %C[hi],r1\n\tadc %D[hi],%[z]\n\t"
      "mul %D[a],%C[b]\n\tadd %B[hi],r0\n\tadc %C[hi],r1\n\tadc %D[hi],%[z]\n\t"
      "clr __zero_reg__"
      : [lo] "=&r"(p.low), [hi] "=&r"(p.high), [z] "=&r"(zero)
      : [a] "r"(a), [b] "r"(b)
      : "r0", "r1");
#else
  const uint64_t product = static_cast<uint64_t>(a) * b;
  p.high = static_cast<uint32_t>(product >> 32);
  p.low = static_cast<uint32_t>(product);
#endif
  return p;
}

int32_t mul_q30_narrow(int32_t a, uint32_t x) {
  const bool negative = a < 0;
  const uint32_t magnitude = negative ? 0u - static_cast<uint32_t>(a) : static_cast<uint32_t>(a);
  const WideProduct p = mul_wide(magnitude, x);
  // (the low word's top two bits from its top byte: avr-gcc shifts a word by 30 in a loop)
  uint32_t q = (p.high << 2) | static_cast<uint8_t>(static_cast<uint8_t>(p.low >> 24) >> 6);
  if (!negative) return static_cast<int32_t>(q);
  if ((p.low & 0x3fffffffu) != 0) ++q;  // toward minus infinity
  return -static_cast<int32_t>(q);
}

int64_t clamp64(int64_t a, int64_t lo, int64_t hi) { return a < lo ? lo : (a > hi ? hi : a); }

uint32_t isqrt64(uint64_t x) {
  uint64_t root = 0;
  uint64_t bit = static_cast<uint64_t>(1) << 62;
  while (bit > x) bit >>= 2;
  while (bit != 0) {
    if (x >= root + bit) {
      x -= root + bit;
      root = (root >> 1) + bit;
    } else {
      root >>= 1;
    }
    bit >>= 2;
  }
  return static_cast<uint32_t>(root);
}

namespace {

// sin(pi/2 x) = x (c1 + x^2 (c3 + ... + x^2 c13)) on [0, 1]: the Taylor coefficients of
// sin(pi/2 x) in Q30 (the next term is below 1e-9 there).
const int64_t kSinCoefficients[] = {
    1686629713,  // c1  =  pi/2
    -693598668,  // c3  = -(pi/2)^3 / 3!
    85569306,    // c5  =  (pi/2)^5 / 5!
    -5026995,    // c7  = -(pi/2)^7 / 7!
    172272,      // c9  =  (pi/2)^9 / 9!
    -3864,       // c11 = -(pi/2)^11 / 11!
    61,          // c13 =  (pi/2)^13 / 13!
};

// 2^f = e^(f ln 2) for f in [0, 1): Taylor coefficients (ln 2)^k / k! in Q30, k = 0..10 (the
// next term is below 2^-30).
const int64_t kExp2Coefficients[] = {
    1073741824, 744261118, 257941248, 59597083, 10327387, 1431680, 165394, 16377, 1419, 109, 8,
};

}  // namespace

int32_t sin_turns(uint32_t phase) {
  // Quadrant and the position within it, x in Q30 of a quarter turn.
  const uint32_t quadrant = phase >> 30;
  int64_t x = static_cast<int64_t>(phase & 0x3fffffffu);
  if (quadrant & 1u) x = (static_cast<int64_t>(1) << 30) - x;
  const int64_t x2 = mul_q30(x, x);
  int64_t acc = kSinCoefficients[6];
  for (int i = 5; i >= 0; --i) acc = kSinCoefficients[i] + mul_q30(acc, x2);
  int64_t s = mul_q30(acc, x);
  if (s > (static_cast<int64_t>(1) << 30)) s = static_cast<int64_t>(1) << 30;
  return static_cast<int32_t>(quadrant & 2u ? -s : s);
}

int64_t exp2_q30(int64_t x) {
  if (x > (static_cast<int64_t>(1) << 30)) x = static_cast<int64_t>(1) << 30;
  const int64_t whole = shift_floor(x, 30);  // <= 1
  const int64_t f = x - whole * (static_cast<int64_t>(1) << 30);
  int64_t acc = kExp2Coefficients[10];
  for (int i = 9; i >= 0; --i) acc = kExp2Coefficients[i] + mul_q30(acc, f);
  if (whole >= 0) return acc * (static_cast<int64_t>(1) << whole);
  if (whole <= -62) return 0;
  return static_cast<int64_t>(static_cast<uint64_t>(acc) >> static_cast<unsigned>(-whole));
}

}  // namespace device
}  // namespace avar
