#pragma once
// Integer arithmetic of the device engine: fixed-point products, shifts that round toward minus
// infinity on every target, an integer square root, and sin and 2^x by polynomials in Q30. Every
// function is a pure function of its arguments, built from +, -, *, shifts and compares of fixed
// width integers, so that the host, AVR, Cortex-M and RISC-V builds give the same bits.
// Freestanding C++14: no floating point, no library beyond <stdint.h>.
//
// Formats: Qn is a signed or unsigned integer holding x * 2^n; a "turn" phase is a uint32_t
// holding the fraction of a full circle times 2^32 (it wraps as angles do).

#include <stdint.h>

namespace avar {
namespace device {

/// 1 in Q30.
const int64_t kQ30 = static_cast<int64_t>(1) << 30;

/// x / 2^n rounded toward minus infinity (an arithmetic shift, spelled out: C++14 leaves the
/// shift of a negative number to the compiler). 0 <= n < 64. Out of line, as the other helpers
/// here: on an 8-bit target each 64-bit operation inlined is a hundred instructions.
int64_t shift_floor(int64_t x, unsigned n);

/// a * b / 2^30, toward minus infinity. |a| * b must fit in 63 bits.
int64_t mul_q30(int64_t a, int64_t b);

/// The 64-bit product of two 32-bit numbers as its two words. On AVR, sixteen byte products with
/// the MUL instruction (about 100 cycles; avr-gcc makes a 64-bit product a library call of several
/// hundred); elsewhere the compiler's widening multiply. The device tests compare the two bit for
/// bit (the AVR build against the host's under simavr). Out of line: one copy of the 16 products.
struct WideProduct {
  uint32_t high, low;
};
WideProduct mul_wide(uint32_t a, uint32_t b);

/// a * x / 2^30 toward minus infinity, as mul_q30, for 0 <= x <= 2^30 (the result fits 32 bits).
int32_t mul_q30_narrow(int32_t a, uint32_t x);

/// a clamped to [lo, hi].
int64_t clamp64(int64_t a, int64_t lo, int64_t hi);

/// floor(sqrt(x)), by the digit-by-digit method: 32 fixed steps.
uint32_t isqrt64(uint64_t x);

/// sin(2 pi phase / 2^32) in Q30, within 2^-27 of the true value.
int32_t sin_turns(uint32_t phase);
/// cos(2 pi phase / 2^32) in Q30.
inline int32_t cos_turns(uint32_t phase) { return sin_turns(phase + 0x40000000u); }

/// 2^(x / 2^30) in Q30 for x <= 2^30 (so at most 2^31), relative error below 2^-26; 0 when the
/// result is below 2^-30.
int64_t exp2_q30(int64_t x);

}  // namespace device
}  // namespace avar
