// The Servo API an exported avar library uses for servos on pins, as the Arduino cores declare it
// (the AVR, RP2040 and STM32 cores' Servo library; ESP32Servo's is the same). See Arduino.h.
#pragma once
#include <Arduino.h>

class Servo {
 public:
  Servo();
  uint8_t attach(int pin);
  void detach();
  void writeMicroseconds(int value);
  bool attached();
};
