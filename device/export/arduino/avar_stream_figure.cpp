// The Arduino side of a streaming board: Serial carries the avar-device protocol, Wire drives the
// PCA9685 boards, micros() times the control ticks. Everything else is avar's (src/avar/...).
#include "avar_stream_figure.h"

#include <Wire.h>

#include "avar_wire_io.h"

#include "avar/device/stream_figure.hpp"
#include "avar_stream.h"

namespace avar_stream_figure {
namespace {

using namespace avar::device;

StreamFigureStorage<AVAR_CHANNEL_COUNT, AVAR_BOARD_COUNT, AVAR_KNOTS> storage;
StreamFigure& figure = storage.figure;
uint8_t reply[stream_reply_room(AVAR_CHANNEL_COUNT)];
bool opened = false;
uint32_t next_tick_us = 0;
const uint32_t kTickUs = 1000000UL / AVAR_RATE_HZ;

const FigureIo& io = avar_wire_io::io;

// Every byte avar sent since the last call; an answer goes out as soon as its frame is complete.
void receive() {
  while (Serial.available() > 0) {
    const uint16_t n = stream_receive(figure.player, static_cast<uint8_t>(Serial.read()), micros(), reply);
    if (n > 0) Serial.write(reply, n);
  }
}

}  // namespace

bool begin() {
  Serial.begin(AVAR_SERIAL_BAUD);
  Wire.begin();
  // At 400 kHz a tick's writes (6 bytes per channel that moved) take about 1.2 ms for 8 channels:
  // the serial port's receive buffer (64 bytes on an Uno) holds what arrives meanwhile.
  Wire.setClock(400000);
  opened = storage.open(avar_stream::kFigure, sizeof avar_stream::kFigure, AVAR_WATCHDOG_US) == kFigureOk;
  if (!opened) return false;
  const bool started = stream_figure_begin(figure, io) == kFigureOk;
  next_tick_us = micros();
  return started;
}

void run() {
  if (!opened) return;
  receive();
  // Ticks due since the last call, each at its own time; a long stall is caught up by at most
  // four ticks, then the clock moves on.
  for (uint8_t i = 0; i < 4 && static_cast<int32_t>(micros() - next_tick_us) >= 0; ++i) {
    stream_figure_tick(figure, next_tick_us, io);
    next_tick_us += kTickUs;
    receive();
  }
  if (static_cast<int32_t>(micros() - next_tick_us) >= 0) next_tick_us = micros() + kTickUs;
}

}  // namespace avar_stream_figure
