// A streaming board: the figure record of the streaming-head rig (its avar-device link's outputs on
// a PCA9685, the streaming limits at the board's rate), the board started at rest, knots streamed
// to it played on the PCA9685's registers through the same codec the boards decode, a channel
// released by avar switched off, and a silent board releasing every servo.
#include "avar/device/stream_figure.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "avar/config/rig_file.hpp"
#include "avar/device/figure_export.hpp"
#include "avar/firmware_iface/pca9685_codec.hpp"

namespace avar::device {
namespace stream_figure_tests {
namespace {

namespace pca9685 = firmware_iface::pca9685;
namespace wire = firmware_iface::avar_device;

struct Bus {
  pca9685::Registers board{};
  bool answering = true;
  Bus() { pca9685::power_on(board); }
};

FigureIo io_for(Bus& bus) {
  return {[](void* context, std::uint8_t address, const std::uint8_t* bytes, std::uint8_t length) {
            auto& b = *static_cast<Bus*>(context);
            return b.answering && address == 0x40 && pca9685::apply(b.board, bytes, length);
          },
          [](void*, std::uint16_t) {}, nullptr, &bus};
}

struct Board {
  FigureSpec spec;
  std::vector<std::uint8_t> record;
  StreamFigureStorage<8, 1, 16> storage{};
  StreamFigure& figure = storage.figure;
  std::uint32_t now = 0;

  Board() {
    spec = stream_figure_from_rig(config::load_rig_file(AVAR_SOURCE_DIR "/examples/rigs/streaming-head.yaml"));
    record = encode_figure_record(spec);
  }
  void feed(const std::uint8_t* bytes, std::size_t size) {
    std::uint8_t reply[wire::kMaxFrame];
    for (std::size_t i = 0; i < size; ++i) (void)stream_receive(figure.player, bytes[i], now, reply);
  }
  std::uint16_t expected_counts(std::size_t c) const {
    const std::int32_t ns = figure_pulse_ns(storage.outputs[c], storage.channels[c].output);
    return pca9685::counts_for_pulse_ns(static_cast<std::uint32_t>(ns), storage.boards[0].clock_hz, storage.boards[0].prescale);
  }
};

TEST(StreamFigure, TheRecordIsTheLinksOutputsOnAPca9685AtTheBoardsRate) {
  Board b;
  EXPECT_EQ(b.spec.rate, 200u) << "the link's device_rate";
  ASSERT_EQ(b.spec.boards.size(), 1u);
  EXPECT_EQ(b.spec.boards[0].address, 0x40);
  ASSERT_EQ(b.spec.channels.size(), 8u);
  EXPECT_EQ(b.spec.channels[4].output, 4);
  EXPECT_EQ(b.spec.channels[4].at_low_ns, 1900000) << "eyes_pan is reversed";
  const ChannelLimits standalone = device_limits(b.spec.channels[0].range, 0, 300, 8000, 0, 200);
  EXPECT_EQ(b.spec.channels[0].limits.speed, standalone.speed);
  EXPECT_GT(b.spec.channels[0].limits.accel, standalone.accel) << "the streaming headroom";
  EXPECT_THROW(stream_figure_from_rig(config::load_rig_file(AVAR_SOURCE_DIR "/examples/rigs/pca9685-head.yaml")), InputError);
}

TEST(StreamFigure, PlaysStreamedKnotsOnTheBoardsRegisters) {
  Board b;
  ASSERT_EQ(b.storage.open(b.record.data(), static_cast<std::uint32_t>(b.record.size()), 500000), kFigureOk);
  Bus bus;
  const FigureIo io = io_for(bus);
  ASSERT_EQ(stream_figure_begin(b.figure, io), kFigureOk);
  for (std::size_t c = 0; c < 8; ++c)
    EXPECT_EQ(pca9685::pulse_counts(bus.board, b.storage.outputs[c].output), b.expected_counts(c));
  std::uint8_t out[wire::kMaxFrame];
  b.feed(out, wire::encode_time(0, out));
  // neck_pan (output 1) to 30 degrees of -60..60 in a knot 100 ms ahead, the others at rest.
  std::vector<wire::Knot> knots(8);
  for (std::size_t c = 0; c < 8; ++c) knots[c] = {b.storage.channels[c].output, 0};
  knots[1].value = static_cast<std::uint16_t>(std::lround(90.0 / 120.0 * 65535));
  b.feed(out, wire::encode_knots(100000, knots.data(), 8, out));
  for (int tick = 0; tick < 200; ++tick) {
    if (tick % 20 == 0) b.feed(out, wire::encode_time(b.now, out));  // avar's clock keeps the link alive
    stream_figure_tick(b.figure, b.now, io);
    b.now += 5000;
    for (std::size_t c = 0; c < 8; ++c)
      ASSERT_EQ(pca9685::pulse_counts(bus.board, b.storage.outputs[c].output), b.expected_counts(c)) << "tick " << tick;
  }
  EXPECT_EQ(b.storage.channels[1].output, knots[1].value) << "neck_pan arrived";
  // avar releases neck_pan: its output goes fully off, the others keep their pulses.
  const std::uint8_t mask = 1u << 1;
  b.feed(out, wire::encode_release_channels(&mask, 1, out));
  stream_figure_tick(b.figure, b.now, io);
  EXPECT_EQ(pca9685::pulse_counts(bus.board, 1), 0);
  EXPECT_EQ(pca9685::pulse_counts(bus.board, 0), b.expected_counts(0));
  EXPECT_FALSE(b.figure.io_fault);
}

TEST(StreamFigure, ASilentBoardReleasesEveryServo) {
  Board b;
  ASSERT_EQ(b.storage.open(b.record.data(), static_cast<std::uint32_t>(b.record.size()), 500000), kFigureOk);
  Bus bus;
  const FigureIo io = io_for(bus);
  ASSERT_EQ(stream_figure_begin(b.figure, io), kFigureOk);
  std::uint8_t out[wire::kMaxFrame];
  b.feed(out, wire::encode_time(0, out));
  std::vector<wire::Knot> knots(8, wire::Knot{60000, 0});
  b.feed(out, wire::encode_knots(0, knots.data(), 8, out));
  bus.answering = false;
  for (int tick = 0; tick < 20 && !b.figure.io_fault; ++tick) {
    stream_figure_tick(b.figure, b.now, io);
    b.now += 5000;
  }
  EXPECT_TRUE(b.figure.io_fault);
  EXPECT_EQ(b.figure.player.state, wire::kFault) << "the status avar reads says so";
  bus.answering = true;
  const std::uint16_t frozen = b.storage.channels[0].output;
  stream_figure_tick(b.figure, b.now, io);
  EXPECT_EQ(b.storage.channels[0].output, frozen) << "a released board's figure stays still";

  std::vector<std::uint8_t> damaged = b.record;
  damaged[3] = 'x';
  StreamFigureStorage<8, 1, 16> other{};
  EXPECT_EQ(other.open(damaged.data(), static_cast<std::uint32_t>(damaged.size()), 500000), kFigureBadRecord);
}

}  // namespace
}  // namespace stream_figure_tests
}  // namespace avar::device
