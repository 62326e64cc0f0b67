#pragma once
// avar_stream_figure: a streaming board exported by `avar export --stream`. avar, on a PC or a
// Raspberry Pi, sends this board curve knots over the serial port (the avar-device protocol: each
// channel's value and slope a little ahead of time, and avar's clock); the board plays the curve
// between them at its own control rate on servos on PCA9685 boards, through the channels' limits
// (avar_stream.h, avar_stream.cpp: the figure record, generated; do not edit).
//
// Safety, on the board: every output passes the channel's range, speed and acceleration limits;
// at power-up every servo glides from rest; a link silent for the watchdog time, or avar's stop,
// eases to rest; avar's release switches outputs off; a PCA9685 that stops answering switches
// every output off, the figure stays still until the board is reset, and avar is told at its next
// start (the board's state: fault).
//
// Serial (AVAR_SERIAL_BAUD: the rig link's baud) is avar's link alone: print nothing on it.

#include <Arduino.h>

namespace avar_stream_figure {

/// Starts Serial and Wire (I2C at 400 kHz), checks the figure record and starts the boards with
/// every servo at rest. Returns false when the record does not check (the board then stays silent
/// and avar reports that it does not answer) or a PCA9685 does not answer (every output off).
bool begin();
/// Call from loop(), as often as it comes round: avar's bytes in, the board's answers out, and
/// the control ticks that are due.
void run();

}  // namespace avar_stream_figure
