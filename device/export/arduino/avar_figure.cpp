// The Arduino side of an exported figure: Wire for the boards, Servo for servos on pins, micros()
// for the control ticks, Serial and a pin for the triggers. Everything else is the device engine's
// (src/avar/...).
#include "avar_figure.h"

#include <Wire.h>

#include "avar/device/figure.hpp"
#include "avar_shows.h"
#include "avar_wire_io.h"
#if AVAR_PIN_COUNT > 0
#include "avar_pin_io.h"
#endif

namespace avar_figure {
namespace {

using namespace avar::device;

FigureStorage<AVAR_CHANNEL_COUNT, AVAR_BOARD_COUNT> storage;
Figure& figure = storage.figure;
bool running = false;
uint32_t next_tick_us = 0;
const uint32_t kTickUs = 1000000UL / AVAR_RATE_HZ;
// The start button: a press counts once the pin stayed low (pulled up) for this long.
const uint32_t kDebounceMs = 20;
bool button_down = false;
uint32_t button_since_ms = 0;

#if AVAR_PIN_COUNT > 0
const FigureIo io = {avar_wire_io::i2c_write, avar_wire_io::wait_us, avar_pin_io::pulse, nullptr};
#else
const FigureIo& io = avar_wire_io::io;
#endif

void say(const __FlashStringHelper* text) {
  Serial.print(F("avar: "));
  Serial.println(text);
}

void poll_button() {
#if AVAR_BUTTON_PIN >= 0
  const bool down = digitalRead(AVAR_BUTTON_PIN) == LOW;
  const uint32_t now = millis();
  if (down != button_down) {
    button_down = down;
    button_since_ms = now;
    return;
  }
  if (down && button_since_ms != 0 && now - button_since_ms >= kDebounceMs) {
    button_since_ms = 0;  // once per press
    start(AVAR_BUTTON_SHOW);
  }
#endif
}

}  // namespace

bool begin() {
  Serial.begin(AVAR_SERIAL_BAUD);
#if AVAR_BOARD_COUNT > 0
  Wire.begin();
#endif
#if AVAR_BUTTON_PIN >= 0
  pinMode(AVAR_BUTTON_PIN, INPUT_PULLUP);
#endif
  const FigureStatus opened = storage.open(avar_shows::kFigure, sizeof avar_shows::kFigure, avar_shows::kShows, AVAR_SHOW_COUNT);
  if (opened != kFigureOk) {
    say(opened == kFigureBadShow ? F("a show does not check (export again with this avar)")
                                 : F("the figure record does not check (export again with this avar)"));
    return false;
  }
  if (figure_begin(figure, io) != kFigureOk) {
    say(F("a PCA9685 board does not answer on I2C: servos released"));
    return false;
  }
  running = true;
#if AVAR_BOOT_SHOW >= 0
  start(AVAR_BOOT_SHOW);
#endif
  next_tick_us = micros();
  return true;
}

void run() {
  if (!running) return;
  while (Serial.available() > 0) figure_command(figure, static_cast<uint8_t>(Serial.read()));
  poll_button();
#if AVAR_IDLE_SHOW >= 0
  if (figure.player.mode == kPlayerResting) start(AVAR_IDLE_SHOW);
#endif
  // Ticks due since the last call; a long stall is caught up by at most four ticks, then the
  // clock moves on (the show runs late rather than racing).
  for (uint8_t i = 0; i < 4 && static_cast<int32_t>(micros() - next_tick_us) >= 0; ++i) {
    figure_tick(figure, io);
    next_tick_us += kTickUs;
  }
  if (static_cast<int32_t>(micros() - next_tick_us) >= 0) next_tick_us = micros() + kTickUs;
  if (figure.io_fault) {
    running = false;
    say(F("a PCA9685 board stopped answering: servos released"));
  }
}

bool start(uint8_t index) { return running && player_start(figure.player, index) == kPlayerOk; }

void stop() { player_stop(figure.player); }

bool moving() { return figure.player.mode != kPlayerResting; }

}  // namespace avar_figure
