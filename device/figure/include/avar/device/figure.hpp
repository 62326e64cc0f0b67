#pragma once
// A figure on a device: the player (player.hpp) with its channels' limits, and the outputs they
// drive, read from a figure record in flash that the host's exporter wrote from the rig (avar
// export). The outputs are servo pulses on PCA9685 boards, written through the caller's I2C
// function with avar's PCA9685 codec, or on the board's own pins, handed to the caller's pin
// function in whole µs; the pulse of each channel is a straight line from its pulse at output 0 to
// its pulse at output 65535 (the rig's calibration, reverse and trim included).
// Caller-owned storage, no heap, freestanding C++14; one control tick per figure_tick() call.
//
// Figure record (little-endian):
//   0  "avf1"          magic
//   4  u8  version (kFigureVersion)
//   5  u8  channel count (1..kMaxChannels; every show image has this many)
//   6  u8  board count (0..kMaxBoards; 0 when every channel is on a pin)
//   7  u8  0
//   8  u16 control ticks per second (the player's rate)
//   10 u16 pin pulses per second (the pins' servo frequency; 0 when no channel is on a pin)
//   12 boards, 8 bytes each: u8 7-bit I2C address, u8 prescale, u8 flags (bit 0 totem-pole
//      outputs), u8 0, u32 oscillator clock (Hz)
//   then channels, 60 bytes each: the channel's limits as stored (kLimitsSize bytes, write_limits:
//      Q16 output units and control ticks; the player reads them from here each tick), u8 board
//      (kPinOutput: the board's own pin), u8 output (0..15 on a board; the pin number), u16 0,
//      i32 pulse at output 0 (ns), i32 pulse at output 65535 (ns)

#include <stdint.h>

#include "avar/device/player.hpp"

namespace avar {
namespace device {

const uint8_t kFigureVersion = 2;
const uint8_t kMaxBoards = 8;
/// A channel's board byte for an output on the device's own pin (a hobby servo on a timer PWM pin).
const uint8_t kPinOutput = 0xffu;
/// The pulses a pin output may ask for (ns): what the boards' Servo libraries put out (544 to
/// 2400 µs, their attach() defaults).
const int32_t kMinPinPulseNs = 544000, kMaxPinPulseNs = 2400000;
const uint32_t kFigureHeaderSize = 12, kFigureBoardSize = 8, kFigureChannelSize = kLimitsSize + 12;
/// Pulse widths the record may ask for (ns): a hobby servo's 0.1 to 5 ms.
const int32_t kMinPulseNs = 100000, kMaxPulseNs = 5000000;

struct FigureBoard {
  uint8_t address;
  uint8_t prescale;
  bool totem_pole;
  uint32_t clock_hz;
};

struct FigureOutput {
  uint8_t board;                  ///< index into the boards, or kPinOutput
  uint8_t output;                 ///< the board's output, or the pin
  int32_t at_low_ns, at_high_ns;  ///< the pulse at output 0 and at 65535
  uint16_t counts;                ///< what the board (counts) or pin (µs) was last told (kNoCounts: nothing yet)
};
const uint16_t kNoCounts = 0xffffu;
const uint16_t kOffCounts = 0xfffeu;  ///< the output was switched fully off

/// How the figure reaches its boards and pins: the caller's functions.
struct FigureIo {
  /// One I2C write transaction to `address` (7-bit); false when the board did not acknowledge.
  bool (*i2c_write)(void* context, uint8_t address, const uint8_t* bytes, uint8_t length);
  /// Waits at least `us` microseconds (a board's oscillator start-up).
  void (*wait_us)(void* context, uint16_t us);
  /// A hobby servo's pulse on `pin`, `us` microseconds long each period (544..2400), or no pulses
  /// at all when `us` is 0 (the servo goes limp). Called only when the pulse changes. nullptr for a
  /// figure without pin outputs.
  void (*pin_pulse)(void* context, uint8_t pin, uint16_t us);
  void* context;
};

struct Figure {
  Player player;
  FigureOutput* outputs;  ///< one per channel
  FigureBoard* boards;
  uint8_t board_count;
  uint16_t rate;  ///< control ticks per second
  bool io_fault;  ///< a board did not acknowledge a write: the figure released its outputs
};

enum FigureStatus : uint8_t {
  kFigureOk = 0,
  kFigureBadRecord,  ///< not a figure record, or one that does not fit the storage given
  kFigureBadShow,    ///< a show image that does not check, or whose channels are not the figure's
  kFigureBadLimits,  ///< a channel's limits the limiter cannot use
  kFigureNoBoard,    ///< a board did not acknowledge its start-up
};

/// Reads `record` (from flash, through AVAR_DEVICE_READ_BYTE) into the caller's storage (room for
/// `channel_capacity` channels and `board_capacity` boards) and sets the player up at rest, the
/// shows checked. The channels' limits stay in the record (read each tick): keep it in place.
FigureStatus figure_open(Figure& figure, const uint8_t* record, uint32_t size, PlayerChannel* channels, FigureOutput* outputs,
                         uint8_t channel_capacity, FigureBoard* boards, uint8_t board_capacity, const PlayerShow* shows,
                         uint8_t show_count);
/// Starts every board (sleep, prescale, outputs, wake, oscillator start-up, restart) and sends
/// every channel its rest pulse. kFigureNoBoard (and every output released) when a board is silent.
FigureStatus figure_begin(Figure& figure, const FigureIo& io);
/// One control tick: the player's tick, then each channel's pulse to its board where it changed.
/// A board that does not acknowledge releases every output (io_fault) and the figure stays still.
void figure_tick(Figure& figure, const FigureIo& io);
/// A figure with its storage for `Channels` channels and `Boards` boards (0: pins only; a board's
/// sketch keeps one as a global).
template <uint8_t Channels, uint8_t Boards>
struct FigureStorage {
  PlayerChannel channels[Channels];
  FigureOutput outputs[Channels];
  FigureBoard boards[Boards == 0 ? 1 : Boards];
  Figure figure;

  FigureStatus open(const uint8_t* record, uint32_t size, const PlayerShow* shows, uint8_t show_count) {
    return figure_open(figure, record, size, channels, outputs, Channels, boards, Boards, shows, show_count);
  }
};

/// Every output of every board and every pin fully off (a servo without pulses goes limp): the fail-safe. The
/// figure stays released (io_fault) until it is opened and begun again.
void figure_release(Figure& figure, const FigureIo& io);

// The record and the boards, for any player that drives a figure's outputs (this one's, the
// streaming player's: stream_figure.hpp).

/// What a figure record holds.
struct FigureShape {
  uint8_t channel_count, board_count;
  uint16_t rate;      ///< control ticks per second
  uint16_t pin_rate;  ///< pin pulses per second (0: no pin outputs)
};
/// Reads a figure record's boards and outputs into the caller's storage (room for
/// `channel_capacity` outputs and `board_capacity` boards), checked whole.
FigureStatus figure_read_record(const uint8_t* record, uint32_t size, FigureOutput* outputs, uint8_t channel_capacity,
                                FigureBoard* boards, uint8_t board_capacity, FigureShape& shape);
/// Channel c's stored limits inside the record (read in place, kLimitsSize bytes).
const uint8_t* figure_channel_limits(const uint8_t* record, const FigureShape& shape, uint8_t channel);
/// The first step of opening either player's figure (`FigureT`: Figure or StreamFigure): the
/// record's boards and outputs into the caller's storage, each channel's limits pointed into the
/// record (`ChannelT`: anything with a `limits` pointer), and the figure's own fields.
template <class FigureT, class ChannelT>
FigureStatus figure_attach(FigureT& f, const uint8_t* record, uint32_t size, ChannelT* channels, FigureOutput* outputs,
                           uint8_t channel_capacity, FigureBoard* boards, uint8_t board_capacity, FigureShape& shape) {
  f.outputs = outputs;
  f.boards = boards;
  f.board_count = 0;
  f.rate = 0;
  f.io_fault = false;
  shape.channel_count = 0;
  shape.board_count = 0;
  shape.rate = 0;
  shape.pin_rate = 0;
  const FigureStatus read = figure_read_record(record, size, outputs, channel_capacity, boards, board_capacity, shape);
  if (read != kFigureOk) return read;
  for (uint8_t c = 0; c < shape.channel_count; ++c) channels[c].limits = figure_channel_limits(record, shape, c);
  f.board_count = shape.board_count;
  f.rate = shape.rate;
  return kFigureOk;
}
/// Every board's start-up (figure_begin's first step); false when a board does not acknowledge.
bool figure_boards_start(const FigureBoard* boards, uint8_t board_count, const FigureIo& io);
/// An output's pulse for a 16-bit value, written only when its board (or pin) was told otherwise;
/// false when the board does not acknowledge.
bool figure_output_write(FigureOutput& output, const FigureBoard* boards, const FigureIo& io, uint16_t value);
/// An output fully off (its servo goes limp), written once; false when the board does not acknowledge.
bool figure_output_off(FigureOutput& output, const FigureBoard* boards, const FigureIo& io);
/// Every output of every board fully off at once, and every pin output off.
void figure_boards_off(const FigureBoard* boards, uint8_t board_count, FigureOutput* outputs, uint8_t channel_count,
                       const FigureIo& io);

/// The pulse (ns) of a 16-bit output: at_low + (at_high - at_low) * output / 65535, rounded.
int32_t figure_pulse_ns(const FigureOutput& output, uint16_t value);

/// A serial command byte: '1'..'9' start show 1..9 (of those there are), 's' or '0' stop (ease to
/// rest). Other bytes (line ends) are ignored. Returns whether the byte was a command it obeyed.
bool figure_command(Figure& figure, uint8_t byte);

}  // namespace device
}  // namespace avar
