#include "avar/device/figure.hpp"

#include "avar/device/show_image.hpp"
#include "avar/firmware_iface/pca9685_codec.hpp"

namespace avar {
namespace device {
namespace {

namespace pca9685 = firmware_iface::pca9685;

bool send(const FigureIo& io, uint8_t address, const pca9685::Write& w) {
  const bool acknowledged = io.i2c_write(io.context, address, w.bytes, w.length);
  if (acknowledged && w.wait_us != 0) io.wait_us(io.context, w.wait_us);
  return acknowledged;
}

}  // namespace

bool figure_output_write(FigureOutput& out, const FigureBoard* boards, const FigureIo& io, uint16_t value) {
  const int32_t ns = figure_pulse_ns(out, value);
#if AVAR_DEVICE_PINS
  if (out.board == kPinOutput) {
    const uint16_t us = static_cast<uint16_t>((ns + 500) / 1000);
    if (us != out.counts) io.pin_pulse(io.context, out.output, us);
    out.counts = us;
    return true;
  }
#endif
  const FigureBoard& board = boards[out.board];
  const uint16_t counts = pca9685::counts_for_pulse_ns(static_cast<uint32_t>(ns), board.clock_hz, board.prescale);
  if (counts == out.counts) return true;
  if (!send(io, board.address, pca9685::channel_pulse(out.output, counts))) return false;
  out.counts = counts;
  return true;
}

bool figure_output_off(FigureOutput& out, const FigureBoard* boards, const FigureIo& io) {
  if (out.counts == kOffCounts) return true;
#if AVAR_DEVICE_PINS
  if (out.board == kPinOutput) {
    io.pin_pulse(io.context, out.output, 0);
    out.counts = kOffCounts;
    return true;
  }
#endif
  if (!send(io, boards[out.board].address, pca9685::channel_off(out.output))) return false;
  out.counts = kOffCounts;
  return true;
}

bool figure_boards_start(const FigureBoard* boards, uint8_t board_count, const FigureIo& io) {
  for (uint8_t b = 0; b < board_count; ++b) {
    pca9685::Write writes[5];
    const size_t count = pca9685::start_sequence(boards[b].prescale, boards[b].totem_pole, writes);
    for (size_t i = 0; i < count; ++i)
      if (!send(io, boards[b].address, writes[i])) return false;
  }
  return true;
}

void figure_boards_off(const FigureBoard* boards, uint8_t board_count, FigureOutput* outputs, uint8_t channel_count,
                       const FigureIo& io) {
  for (uint8_t b = 0; b < board_count; ++b) send(io, boards[b].address, pca9685::all_off());
  for (uint8_t c = 0; c < channel_count; ++c) {
#if AVAR_DEVICE_PINS
    if (outputs[c].board == kPinOutput && outputs[c].counts != kOffCounts) io.pin_pulse(io.context, outputs[c].output, 0);
#endif
    outputs[c].counts = kNoCounts;
  }
}

int32_t figure_pulse_ns(const FigureOutput& o, uint16_t value) {
  // The span times the output, rounded half away from zero, over 65535: |span| < 2^23, so the
  // product stays below 2^39.
  const int64_t product = (static_cast<int64_t>(o.at_high_ns) - o.at_low_ns) * value;
  const int64_t rounded = product >= 0 ? (product + 32767) / 65535 : -((-product + 32767) / 65535);
  return static_cast<int32_t>(o.at_low_ns + rounded);
}

FigureStatus figure_read_record(const uint8_t* record, uint32_t size, FigureOutput* outputs, uint8_t channel_capacity,
                                FigureBoard* boards, uint8_t board_capacity, FigureShape& shape) {
  ByteReader r = {record, size, 0, false};
  if (r.u8() != 'a' || r.u8() != 'v' || r.u8() != 'f' || r.u8() != '1' || r.u8() != kFigureVersion) return kFigureBadRecord;
  const uint8_t channel_count = r.u8(), board_count = r.u8();
  r.u8();
  const uint16_t rate = static_cast<uint16_t>(r.fixed(2));
  const uint16_t pin_rate = static_cast<uint16_t>(r.fixed(2));
  if (channel_count == 0 || channel_count > channel_capacity || channel_count > kMaxChannels || board_count > board_capacity ||
      board_count > kMaxBoards || rate == 0)
    return kFigureBadRecord;
  if (size != kFigureHeaderSize + kFigureBoardSize * board_count + kFigureChannelSize * static_cast<uint32_t>(channel_count))
    return kFigureBadRecord;
  for (uint8_t b = 0; b < board_count; ++b) {
    FigureBoard& board = boards[b];
    board.address = r.u8();
    board.prescale = r.u8();
    board.totem_pole = (r.u8() & 1u) != 0;
    r.u8();
    board.clock_hz = r.fixed(4);
    if (board.address > 0x7fu || board.prescale < 3 || board.clock_hz == 0) return kFigureBadRecord;
  }
  for (uint8_t c = 0; c < channel_count; ++c) {
    r.at += kLimitsSize;  // read in place by the player (figure_channel_limits)
    FigureOutput& o = outputs[c];
    o.board = r.u8();
    o.output = r.u8();
    r.fixed(2);
    o.at_low_ns = static_cast<int32_t>(r.fixed(4));
    o.at_high_ns = static_cast<int32_t>(r.fixed(4));
    o.counts = kNoCounts;
    const bool pin = o.board == kPinOutput;
    const int32_t low = pin ? kMinPinPulseNs : kMinPulseNs, high = pin ? kMaxPinPulseNs : kMaxPulseNs;
    const bool pulses_ok = o.at_low_ns >= low && o.at_low_ns <= high && o.at_high_ns >= low && o.at_high_ns <= high;
    if (pin ? (pin_rate == 0 || !AVAR_DEVICE_PINS) : (o.board >= board_count || o.output > 15)) return kFigureBadRecord;
    if (!pulses_ok) return kFigureBadRecord;
  }
  if (r.overrun) return kFigureBadRecord;
  shape.channel_count = channel_count;
  shape.board_count = board_count;
  shape.rate = rate;
  shape.pin_rate = pin_rate;
  return kFigureOk;
}

const uint8_t* figure_channel_limits(const uint8_t* record, const FigureShape& shape, uint8_t channel) {
  const uint32_t offset =
      kFigureHeaderSize + kFigureBoardSize * shape.board_count + kFigureChannelSize * static_cast<uint32_t>(channel);
  return record + offset;
}

FigureStatus figure_open(Figure& f, const uint8_t* record, uint32_t size, PlayerChannel* channels, FigureOutput* outputs,
                         uint8_t channel_capacity, FigureBoard* boards, uint8_t board_capacity, const PlayerShow* shows,
                         uint8_t show_count) {
  FigureShape shape;
  const FigureStatus attached =
      figure_attach(f, record, size, channels, outputs, channel_capacity, boards, board_capacity, shape);
  if (attached != kFigureOk) return attached;
  switch (player_init(f.player, channels, shape.channel_count, shows, show_count, shape.rate)) {
    case kPlayerOk: return kFigureOk;
    case kPlayerBadLimits: return kFigureBadLimits;
    default: return kFigureBadShow;
  }
}

FigureStatus figure_begin(Figure& f, const FigureIo& io) {
  bool answered = figure_boards_start(f.boards, f.board_count, io);
  for (uint8_t c = 0; answered && c < f.player.channel_count; ++c) {
    f.outputs[c].counts = kNoCounts;
    answered = figure_output_write(f.outputs[c], f.boards, io, f.player.channels[c].output);
  }
  if (answered) return kFigureOk;
  figure_release(f, io);
  return kFigureNoBoard;
}

void figure_tick(Figure& f, const FigureIo& io) {
  if (f.io_fault) return;
  player_tick(f.player);
  for (uint8_t c = 0; c < f.player.channel_count; ++c) {
    if (!figure_output_write(f.outputs[c], f.boards, io, f.player.channels[c].output)) {
      figure_release(f, io);
      return;
    }
  }
}

void figure_release(Figure& f, const FigureIo& io) {
  f.io_fault = true;
  figure_boards_off(f.boards, f.board_count, f.outputs, f.player.channel_count, io);
}

bool figure_command(Figure& f, uint8_t byte) {
  if (f.io_fault) return false;
  if (byte == 's' || byte == 'S' || byte == '0') {
    player_stop(f.player);
    return true;
  }
  if (byte >= '1' && byte <= '9') return player_start(f.player, static_cast<uint8_t>(byte - '1')) == kPlayerOk;
  return false;
}

}  // namespace device
}  // namespace avar
