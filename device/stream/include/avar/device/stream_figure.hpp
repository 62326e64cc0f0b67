#pragma once
// A streaming board: the streaming player (stream_player.hpp) driving a figure's PCA9685 outputs,
// from a figure record in flash that the host's exporter wrote from the rig (avar export
// --stream): the channels' limits (read in place) and their pulses. What the Arduino glue of a
// streaming export runs; the simulated board runs the player alone. Caller-owned storage, no
// heap, freestanding C++14; one control tick per stream_figure_tick() call.
//
// Safety: the player's (limits, rest at power-up, ease to rest on silence or stop); a channel
// released by avar has its output switched fully off; a board that does not acknowledge releases
// every output (io_fault; the player's state kFault, which avar reads in the status) and the figure
// stays still until it is opened and begun again.

#include <stdint.h>

#include "avar/device/figure.hpp"
#include "avar/device/stream_player.hpp"

namespace avar {
namespace device {

struct StreamFigure {
  StreamPlayer player;
  FigureOutput* outputs;  ///< one per channel
  FigureBoard* boards;
  uint8_t board_count;
  uint16_t rate;  ///< control ticks per second (the record's)
  bool io_fault;
};

/// Reads `record` into the caller's storage and sets the streaming player up at rest, holding
/// `knot_capacity` knot frames (`times`: knot_capacity entries, `knots`: knot_capacity * channels),
/// its parser in `frame` (stream_frame_room(channel_capacity) bytes), and easing to rest after
/// `watchdog_us` of link silence. Keep the record in place.
FigureStatus stream_figure_open(StreamFigure& figure, const uint8_t* record, uint32_t size, StreamChannel* channels,
                                FigureOutput* outputs, uint8_t channel_capacity, FigureBoard* boards, uint8_t board_capacity,
                                uint32_t* times, firmware_iface::avar_device::Knot* knots, uint8_t knot_capacity, uint8_t* frame,
                                uint32_t watchdog_us);
/// Starts every board and sends every channel its rest pulse; kFigureNoBoard (every output
/// released) when a board is silent.
FigureStatus stream_figure_begin(StreamFigure& figure, const FigureIo& io);
/// One control tick at `now_us` (the board's micros()): the player's tick, then each channel's
/// pulse (or off, released) where it changed.
void stream_figure_tick(StreamFigure& figure, uint32_t now_us, const FigureIo& io);

/// The storage of a streaming board of `Channels` channels on `Boards` boards holding `Knots`
/// knot frames (a sketch keeps one as a global).
template <uint8_t Channels, uint8_t Boards, uint8_t Knots>
struct StreamFigureStorage {
  StreamChannel channels[Channels];
  FigureOutput outputs[Channels];
  FigureBoard boards[Boards];
  uint32_t times[Knots];
  firmware_iface::avar_device::Knot knots[Knots * Channels];
  uint8_t frame[stream_frame_room(Channels)];
  StreamFigure figure;

  FigureStatus open(const uint8_t* record, uint32_t size, uint32_t watchdog_us) {
    return stream_figure_open(figure, record, size, channels, outputs, Channels, boards, Boards, times, knots, Knots, frame,
                              watchdog_us);
  }
};

}  // namespace device
}  // namespace avar
