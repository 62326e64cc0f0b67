#pragma once
// The figure's I2C on an Arduino: the Wire library's transactions, delayMicroseconds for waits.
// Shared by both kinds of exported board (avar_figure.cpp, avar_stream_figure.cpp).

#include <Arduino.h>
#include <Wire.h>

#include "avar/device/figure.hpp"

namespace avar_wire_io {

inline bool i2c_write(void*, uint8_t address, const uint8_t* bytes, uint8_t length) {
  Wire.beginTransmission(address);
  Wire.write(bytes, length);
  return Wire.endTransmission() == 0;
}

inline void wait_us(void*, uint16_t us) { delayMicroseconds(us); }

const avar::device::FigureIo io = {i2c_write, wait_us, nullptr, nullptr};

}  // namespace avar_wire_io
