// A figure on the device: the record from a rig, the soft start on the boards, a show played to
// the PCA9685's registers (through the same codec the boards decode), a silent board released,
// serial commands, and damaged records refused whole.
#include <gtest/gtest.h>

#include <string>
#include <map>
#include <vector>

#include "avar/config/rig_file.hpp"
#include "avar/config/show_file.hpp"
#include "avar/device/figure.hpp"
#include "avar/device/figure_export.hpp"
#include "avar/firmware_iface/pca9685_codec.hpp"

namespace avar::device {
namespace {

namespace pca9685 = firmware_iface::pca9685;

const std::string kFigureRig = std::string(AVAR_SOURCE_DIR) + "/examples/rigs/pca9685-head.yaml";
const std::string kFigureShow = std::string(AVAR_SOURCE_DIR) + "/examples/shows/hello-head.yaml";

/// Boards on a simulated I2C bus: each write applied to its board's registers as the chip does.
struct Bus {
  pca9685::Registers board{};
  int address = 0x40;
  bool answering = true;
  int writes = 0;
  int waited_us = 0;
  std::map<int, int> pin_us;  ///< each pin's present pulse (0: none)
  int pin_writes = 0;
  Bus() { pca9685::power_on(board); }
};

FigureIo io_for(Bus& bus) {
  return {[](void* context, std::uint8_t address, const std::uint8_t* bytes, std::uint8_t length) {
            auto& b = *static_cast<Bus*>(context);
            if (!b.answering || address != b.address) return false;
            ++b.writes;
            return pca9685::apply(b.board, bytes, length);
          },
          [](void* context, std::uint16_t us) { static_cast<Bus*>(context)->waited_us += us; },
          [](void* context, std::uint8_t pin, std::uint16_t us) {
            auto& b = *static_cast<Bus*>(context);
            b.pin_us[pin] = us;
            ++b.pin_writes;
          },
          &bus};
}

struct LoadedFigure {
  FigureSpec spec;
  std::vector<std::uint8_t> record;
  std::vector<std::uint8_t> image;
  std::vector<PlayerChannel> channels;
  std::vector<FigureOutput> outputs;
  std::vector<FigureBoard> boards;
  std::vector<PlayerShow> shows;
  Figure figure{};

  FigureStatus open() {
    channels.assign(spec.channels.size(), PlayerChannel{});
    outputs.assign(spec.channels.size(), FigureOutput{});
    boards.assign(spec.boards.size(), FigureBoard{});
    shows = {{image.data(), static_cast<std::uint32_t>(image.size())}};
    return figure_open(figure, record.data(), static_cast<std::uint32_t>(record.size()), channels.data(), outputs.data(),
                       static_cast<std::uint8_t>(channels.size()), boards.data(), static_cast<std::uint8_t>(boards.size()),
                       shows.data(), 1);
  }
};

LoadedFigure load(const std::string& rig_file = kFigureRig) {
  LoadedFigure f;
  const rig::Rig rig = config::load_rig_file(rig_file);
  f.spec = figure_from_rig(rig);
  f.record = encode_figure_record(f.spec);
  const playback::Show show = config::load_show_file(kFigureShow);
  f.image = encode_show_image(show, image_channels(f.spec)).bytes;
  return f;
}

/// The counts board output `o` should show for channel c's present 16-bit output.
std::uint16_t expected_counts(const LoadedFigure& f, std::size_t c) {
  const FigureBoard& b = f.boards[f.outputs[c].board];
  const std::int32_t ns = figure_pulse_ns(f.outputs[c], f.channels[c].output);
  return pca9685::counts_for_pulse_ns(static_cast<std::uint32_t>(ns), b.clock_hz, b.prescale);
}

TEST(DeviceFigure, TheRecordCarriesTheRigsChannelsPulsesAndBoard) {
  const LoadedFigure f = load();
  ASSERT_EQ(f.spec.channels.size(), 8u);
  EXPECT_EQ(f.spec.rate, 50u);
  ASSERT_EQ(f.spec.boards.size(), 1u);
  EXPECT_EQ(f.spec.boards[0].address, 0x40);
  EXPECT_EQ(f.spec.boards[0].prescale, 121);  // round(25 MHz / (4096 * 50 Hz)) - 1
  EXPECT_EQ(f.spec.channels[0].name, "jaw");
  EXPECT_EQ(f.spec.channels[0].at_low_ns, 1200000);
  EXPECT_EQ(f.spec.channels[0].at_high_ns, 1650000);
  EXPECT_EQ(f.spec.channels[4].at_low_ns, 1900000) << "eyes_pan is reversed";
  EXPECT_EQ(f.spec.channels[4].at_high_ns, 1100000);
  EXPECT_EQ(f.spec.channels[7].at_low_ns, 1815000) << "lid_right: reversed, trimmed by 15 us";
  EXPECT_EQ(f.record.size(), kFigureHeaderSize + kFigureBoardSize + 8 * kFigureChannelSize);
}

TEST(DeviceFigure, StartsTheBoardAtRestThenPlaysTheShowOnItsRegisters) {
  LoadedFigure f = load();
  ASSERT_EQ(f.open(), kFigureOk);
  Bus bus;
  const FigureIo io = io_for(bus);
  ASSERT_EQ(figure_begin(f.figure, io), kFigureOk);
  EXPECT_EQ(bus.board.value[pca9685::kPreScale], 121);
  EXPECT_EQ(bus.board.value[pca9685::kMode1] & pca9685::kSleep, 0) << "awake";
  EXPECT_GE(bus.waited_us, 500) << "the oscillator's start-up";
  for (std::size_t c = 0; c < 8; ++c) {
    EXPECT_EQ(pca9685::pulse_counts(bus.board, f.outputs[c].output), expected_counts(f, c)) << "channel " << c << " at rest";
  }
  // jaw rests at 0 deg = 1200 us: 1200 us / (20 ms / 4096) = 245.76 -> the prescale's own period
  EXPECT_NEAR(pca9685::pulse_counts(bus.board, 0), 1200e-6 * 25e6 / 122, 1.0);
  ASSERT_TRUE(figure_command(f.figure, '1'));
  int writes_before = bus.writes, ticks = 0;
  while (ticks < 13 * 50) {
    figure_tick(f.figure, io);
    ++ticks;
    for (std::size_t c = 0; c < 8; ++c)
      ASSERT_EQ(pca9685::pulse_counts(bus.board, f.outputs[c].output), expected_counts(f, c)) << "tick " << ticks;
  }
  EXPECT_GT(bus.writes, writes_before) << "the show moved the servos";
  EXPECT_LT(bus.writes - writes_before, 13 * 50 * 8) << "only changed pulses are written";
  for (int i = 0; i < 50 * 10 && f.figure.player.mode != kPlayerResting; ++i) figure_tick(f.figure, io);
  EXPECT_EQ(f.figure.player.mode, kPlayerResting) << "the show's end eases to rest";
  EXPECT_FALSE(f.figure.io_fault);
}

TEST(DeviceFigure, ASilentBoardReleasesEveryServo) {
  LoadedFigure f = load();
  ASSERT_EQ(f.open(), kFigureOk);
  Bus bus;
  bus.answering = false;
  const FigureIo io = io_for(bus);
  EXPECT_EQ(figure_begin(f.figure, io), kFigureNoBoard);
  EXPECT_TRUE(f.figure.io_fault);
  EXPECT_FALSE(figure_command(f.figure, '1')) << "a released figure starts nothing";

  LoadedFigure g = load();
  ASSERT_EQ(g.open(), kFigureOk);
  Bus quits;
  const FigureIo io2 = io_for(quits);
  ASSERT_EQ(figure_begin(g.figure, io2), kFigureOk);
  ASSERT_TRUE(figure_command(g.figure, '1'));
  for (int i = 0; i < 100; ++i) figure_tick(g.figure, io2);
  quits.answering = false;
  for (int i = 0; i < 100 && !g.figure.io_fault; ++i) figure_tick(g.figure, io2);
  EXPECT_TRUE(g.figure.io_fault) << "a board that stops answering mid-show";
  quits.answering = true;  // the all-off write reaches it once it answers again
  figure_release(g.figure, io2);
  for (std::uint8_t c = 0; c < 16; ++c) EXPECT_EQ(pca9685::pulse_counts(quits.board, c), 0) << "output " << int(c) << " off";
}

TEST(DeviceFigure, SerialCommandsStartAndStopShows) {
  LoadedFigure f = load();
  ASSERT_EQ(f.open(), kFigureOk);
  EXPECT_TRUE(figure_command(f.figure, '1'));
  EXPECT_EQ(f.figure.player.mode, kPlayerPlaying);
  EXPECT_FALSE(figure_command(f.figure, '2')) << "there is one show";
  EXPECT_FALSE(figure_command(f.figure, '\n'));
  EXPECT_TRUE(figure_command(f.figure, 's'));
  EXPECT_EQ(f.figure.player.mode, kPlayerStopping);
}

TEST(DeviceFigure, RefusesDamagedRecordsWhole) {
  LoadedFigure f = load();
  const std::vector<std::uint8_t> good = f.record;
  for (std::size_t length = 0; length < good.size(); ++length) {
    f.record.assign(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(length));
    EXPECT_EQ(f.open(), kFigureBadRecord) << "truncated to " << length;
  }
  f.record = good;
  f.record[3] = '2';
  EXPECT_EQ(f.open(), kFigureBadRecord) << "magic";
  f.record = good;
  f.record[kFigureHeaderSize + kFigureBoardSize + kLimitsSize + 1] = 16;  // channel 0's output
  EXPECT_EQ(f.open(), kFigureBadRecord) << "output 16";
  f.record = good;
  f.record[kFigureHeaderSize + kFigureBoardSize + 3 * 8] ^= 0x40;  // channel 0's speed, its reach kept
  EXPECT_EQ(f.open(), kFigureBadLimits);
  f.record = good;
  f.image[0] = 'x';
  EXPECT_EQ(f.open(), kFigureBadShow);
}

const std::string kPinRig = std::string(AVAR_SOURCE_DIR) + "/examples/rigs/pin-servo-head.yaml";

TEST(DeviceFigure, ServosOnPinsGetTheirPulseInMicrosecondsWhenItChanges) {
  LoadedFigure f = load(kPinRig);
  ASSERT_EQ(f.spec.boards.size(), 0u);
  EXPECT_EQ(f.spec.pin_rate, 50u);
  EXPECT_TRUE(f.spec.channels[0].on_pin);
  EXPECT_EQ(f.spec.channels[0].output, 2);
  EXPECT_EQ(f.record.size(), kFigureHeaderSize + 8 * kFigureChannelSize);
  EXPECT_EQ(f.record[kFigureHeaderSize + kLimitsSize], kPinOutput);
  ASSERT_EQ(f.open(), kFigureOk);
  Bus bus;
  const FigureIo io = io_for(bus);
  ASSERT_EQ(figure_begin(f.figure, io), kFigureOk);
  EXPECT_EQ(bus.writes, 0) << "no I2C without boards";
  EXPECT_EQ(bus.pin_us.at(2), 1200) << "jaw at rest: 1200 us";
  EXPECT_EQ(bus.pin_us.at(9), 1815 - 160) << "lid_right at 20 %: reversed, trimmed";
  ASSERT_TRUE(figure_command(f.figure, '1'));
  int changes = 0;
  for (int tick = 0; tick < 13 * 50; ++tick) {
    const int before = bus.pin_writes;
    figure_tick(f.figure, io);
    changes += bus.pin_writes - before;
    for (std::size_t c = 0; c < 8; ++c) {
      const std::int32_t ns = figure_pulse_ns(f.outputs[c], f.channels[c].output);
      ASSERT_EQ(bus.pin_us.at(f.outputs[c].output), (ns + 500) / 1000) << "channel " << c << " tick " << tick;
    }
  }
  EXPECT_GT(changes, 0);
  EXPECT_LT(changes, 13 * 50 * 8) << "only changed pulses are handed on";
  figure_release(f.figure, io);
  for (const auto& [pin, us] : bus.pin_us) EXPECT_EQ(us, 0) << "pin " << pin << " released";
}

TEST(DeviceFigure, RefusesPinRecordsOutsideTheServoLibrariesRange) {
  LoadedFigure f = load(kPinRig);
  const std::vector<std::uint8_t> good = f.record;
  const std::size_t low = kFigureHeaderSize + kLimitsSize + 4;  // channel 0's pulse at output 0 (ns)
  const std::uint32_t too_short = 543000;
  for (int i = 0; i < 4; ++i) f.record[low + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(too_short >> (8 * i));
  EXPECT_EQ(f.open(), kFigureBadRecord) << "543 us on a pin";
  f.record = good;
  f.record[10] = 0;  // no pin rate
  EXPECT_EQ(f.open(), kFigureBadRecord);
  f.record = good;
  EXPECT_EQ(f.open(), kFigureOk);
}

TEST(DeviceFigure, PulsesFollowTheCalibrationLine) {
  FigureOutput o{0, 0, 1000000, 2000000, kNoCounts};
  EXPECT_EQ(figure_pulse_ns(o, 0), 1000000);
  EXPECT_EQ(figure_pulse_ns(o, 65535), 2000000);
  EXPECT_EQ(figure_pulse_ns(o, 32768), 1500008);  // 1e6 * 32768 / 65535 = 500007.6
  FigureOutput reversed{0, 0, 1900000, 1100000, kNoCounts};
  EXPECT_EQ(figure_pulse_ns(reversed, 65535), 1100000);
  EXPECT_EQ(figure_pulse_ns(reversed, 32768), 1499994);
}

TEST(DeviceFigure, RigsADeviceCannotDriveAreRefusedAtTheirLine) {
  try {
    figure_from_rig(config::load_rig_file(std::string(AVAR_SOURCE_DIR) + "/examples/rigs/hello-head.yaml"));
    FAIL() << "a Maestro rig";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("hello-head.yaml:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("PCA9685"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace avar::device
