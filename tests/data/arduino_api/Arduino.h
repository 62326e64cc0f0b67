// The part of the Arduino core's API an exported avar library uses, declared as the cores declare
// it: enough to compile the library's glue and sketch in a test (there is no Arduino core here).
#pragma once
#include <stddef.h>
#include <stdint.h>

class __FlashStringHelper;
#define F(text) (reinterpret_cast<const __FlashStringHelper*>(text))
#define LOW 0x0
#define HIGH 0x1
#define INPUT_PULLUP 0x2

class HardwareSerial {
 public:
  void begin(unsigned long baud);
  int available();
  int read();
  size_t write(const uint8_t* bytes, size_t length);
  size_t print(const __FlashStringHelper* text);
  size_t println(const __FlashStringHelper* text);
};
extern HardwareSerial Serial;

unsigned long millis();
unsigned long micros();
void delayMicroseconds(unsigned int us);
void pinMode(uint8_t pin, uint8_t mode);
int digitalRead(uint8_t pin);
