#include "avar/device/stream_figure.hpp"

namespace avar {
namespace device {

FigureStatus stream_figure_open(StreamFigure& f, const uint8_t* record, uint32_t size, StreamChannel* channels,
                                FigureOutput* outputs, uint8_t channel_capacity, FigureBoard* boards, uint8_t board_capacity,
                                uint32_t* times, firmware_iface::avar_device::Knot* knots, uint8_t knot_capacity, uint8_t* frame,
                                uint32_t watchdog_us) {
  FigureShape shape;
  const FigureStatus attached =
      figure_attach(f, record, size, channels, outputs, channel_capacity, boards, board_capacity, shape);
  if (attached != kFigureOk) return attached;
  switch (stream_init(f.player, channels, shape.channel_count, times, knots, knot_capacity, frame, shape.rate, watchdog_us)) {
    case kStreamOk: return kFigureOk;
    case kStreamBadLimits: return kFigureBadLimits;
    default: return kFigureBadRecord;
  }
}

namespace {

bool write_outputs(StreamFigure& f, const FigureIo& io) {
  for (uint8_t c = 0; c < f.player.channel_count; ++c) {
    const StreamChannel& ch = f.player.channels[c];
    const bool answered =
        ch.released ? figure_output_off(f.outputs[c], f.boards, io) : figure_output_write(f.outputs[c], f.boards, io, ch.output);
    if (!answered) return false;
  }
  return true;
}

void release(StreamFigure& f, const FigureIo& io) {
  f.io_fault = true;
  stream_fault(f.player);
  figure_boards_off(f.boards, f.board_count, f.outputs, f.player.channel_count, io);
}

}  // namespace

FigureStatus stream_figure_begin(StreamFigure& f, const FigureIo& io) {
  for (uint8_t c = 0; c < f.player.channel_count; ++c) f.outputs[c].counts = kNoCounts;
  if (figure_boards_start(f.boards, f.board_count, io) && write_outputs(f, io)) return kFigureOk;
  release(f, io);
  return kFigureNoBoard;
}

void stream_figure_tick(StreamFigure& f, uint32_t now_us, const FigureIo& io) {
  if (f.io_fault) return;
  stream_tick(f.player, now_us);
  if (!write_outputs(f, io)) release(f, io);
}

}  // namespace device
}  // namespace avar
