#pragma once
// avar_figure: the figure and shows exported by `avar export`, played on this board by avar's
// device engine (the same integer source the host tests bit for bit under emulators). The
// servos sit on PCA9685 boards on I2C or on the board's own pins (the Servo library); the shows,
// the channels' limits and the pulses are data in flash (avar_shows.h, avar_shows.cpp: generated,
// do not edit).
//
// Safety, as on the host: every output passes the channel's range, speed and acceleration limits
// on the board; at power-up every servo glides from rest; stop (and a show's end) eases to rest;
// starting a show in the middle of another moves through the limiter, never jumps; a board that
// stops answering releases every servo (no pulses) and the figure stays still until reset.
//
// Serial (AVAR_SERIAL_BAUD, default 115200): send '1'..'9' to start show 1..9, 's' or '0' to stop.

#include <Arduino.h>

namespace avar_figure {

/// Starts Serial and Wire, checks the exported data, starts the boards with every servo at rest,
/// and the boot show if one was exported. Returns false (every servo released, the reason on
/// Serial) when the data does not check or a board does not answer.
bool begin();
/// Call from loop(), as often as it comes round: serial commands, the start button, and the
/// control ticks that are due (at the rig's rate).
void run();
/// Starts show `index` (0-based, in export order), from any point of another.
bool start(uint8_t index);
/// Eases every servo to rest.
void stop();
/// Whether a show plays (or the figure eases to rest after one).
bool moving();

}  // namespace avar_figure
