// The Wire (I2C) API an exported avar library uses, as the Arduino cores declare it (see Arduino.h).
#pragma once
#include <Arduino.h>

class TwoWire {
 public:
  void begin();
  void setClock(uint32_t frequency);
  void beginTransmission(uint8_t address);
  size_t write(const uint8_t* data, size_t length);
  uint8_t endTransmission();
};
extern TwoWire Wire;
