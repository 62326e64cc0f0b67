#pragma once
// The figure's servos on the board's own pins (AVAR_PINS, generated in avar_shows.h): the core's
// Servo library (ESP32Servo on an ESP32), one pulse each 20 ms, whose width the figure gives in µs
// (544..2400, the libraries' own range) and the library turns into its timer's compare value. A
// pulse of 0 detaches the pin: no pulses, the servo goes limp. The width is set before the pin is
// attached, so the first pulse is already the figure's.

#include <Arduino.h>
#if defined(ARDUINO_ARCH_ESP32)
#include <ESP32Servo.h>
#else
#include <Servo.h>
#endif

namespace avar_pin_io {

const uint8_t kPins[AVAR_PIN_COUNT] = {AVAR_PINS};
Servo servos[AVAR_PIN_COUNT];

inline void pulse(void*, uint8_t pin, uint16_t us) {
  for (uint8_t i = 0; i < AVAR_PIN_COUNT; ++i) {
    if (kPins[i] != pin) continue;
    Servo& servo = servos[i];
    if (us == 0) {
      if (servo.attached()) servo.detach();
      return;
    }
    servo.writeMicroseconds(us);
    if (!servo.attached()) {
      servo.attach(pin);
      servo.writeMicroseconds(us);
    }
    return;
  }
}

}  // namespace avar_pin_io
