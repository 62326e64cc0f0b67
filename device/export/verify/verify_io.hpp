#pragma once
// What an exported board's verification run hashes of its outputs: every I2C write's address and
// bytes, every wait and every pin's pulse (the µs its Servo library is handed, which it turns into
// its timer's compare value), into the Hash the FigureIo's context points at; and its closing
// line. Shared by
// the show player's run and the streaming board's. Freestanding C++14.

#include "avar/device/figure.hpp"
#include "verify_lines.hpp"

namespace avar {
namespace device {

inline bool hash_i2c_write(void* hash, uint8_t address, const uint8_t* bytes, uint8_t length) {
  Hash& h = *static_cast<Hash*>(hash);
  h.add(address, 1);
  for (uint8_t i = 0; i < length; ++i) h.add(bytes[i], 1);
  return true;
}

inline void hash_wait_us(void* hash, uint16_t us) { static_cast<Hash*>(hash)->add(us, 2); }

inline void hash_pin_pulse(void* hash, uint8_t pin, uint16_t us) {
  Hash& h = *static_cast<Hash*>(hash);
  h.add(pin, 1);
  h.add(us, 2);
}

/// The I2C and pins of a run, hashed into `hash` (a global: constant-initialized, as a bare Cortex-M run
/// has no static constructors).
constexpr FigureIo hashing_io(Hash& hash) { return FigureIo{hash_i2c_write, hash_wait_us, hash_pin_pulse, &hash}; }

/// "samples N ticks T": a run's last line.
inline void samples_line(LineSink sink, uint32_t samples, uint32_t ticks) {
  char text[48];
  char* at = put_text(text, "samples ");
  at = put_decimal(at, samples);
  at = put_text(at, " ticks ");
  at = put_decimal(at, ticks);
  *at = 0;
  sink(text);
}

}  // namespace device
}  // namespace avar
