// The PCA9685 codec against its data sheet: the prescale formula's own examples (200 Hz is 0x1e,
// the 3 and 255 ends), the start-up sequence's bytes, a channel's four registers (the data sheet's
// LED0 example: on at 0x199, off at 0x4cc), fully off, and a register file that applies writes as
// the chip does (auto-increment and its wrap, the prescale only asleep, ALL_LED into every channel).
#include <gtest/gtest.h>

#include <vector>

#include "avar/firmware_iface/pca9685_codec.hpp"

namespace avar::firmware_iface::pca9685 {
namespace {

std::vector<std::uint8_t> bytes(const Write& w) { return {w.bytes, w.bytes + w.length}; }

TEST(Pca9685Codec, PrescaleFollowsTheDataSheetsFormula) {
  EXPECT_EQ(prescale_for(kInternalClockHz, 200), 0x1e);  // the data sheet's example
  EXPECT_EQ(prescale_for(kInternalClockHz, 50), 121);    // round(122.07) - 1: hobby servos
  EXPECT_EQ(prescale_for(kInternalClockHz, 1526), 3);    // the fastest
  EXPECT_EQ(prescale_for(kInternalClockHz, 5000), 3);    // clamped to the hardware's floor
  EXPECT_EQ(prescale_for(kInternalClockHz, 24), 253);
  EXPECT_EQ(prescale_for(kInternalClockHz, 10), 255);
  EXPECT_EQ(frequency_mhz(kInternalClockHz, 0x1e), 196888u);  // 25 MHz / (4096 x 31) = 196.89 Hz
  EXPECT_EQ(frequency_mhz(kInternalClockHz, 3), 1525879u);
  EXPECT_EQ(frequency_mhz(kInternalClockHz, 255), 23842u);
}

TEST(Pca9685Codec, APulseInCountsOfTheActualPeriod) {
  const std::uint8_t p = prescale_for(kInternalClockHz, 50);          // a count lasts 122 / 25 MHz = 4.88 us
  EXPECT_EQ(counts_for_pulse_ns(1500000, kInternalClockHz, p), 307);  // 1500 / 4.88 = 307.4
  EXPECT_EQ(counts_for_pulse_ns(1000000, kInternalClockHz, p), 205);  // 204.9
  EXPECT_EQ(counts_for_pulse_ns(2000000, kInternalClockHz, p), 410);  // 409.8
  EXPECT_EQ(counts_for_pulse_ns(0, kInternalClockHz, p), 0);
  EXPECT_EQ(counts_for_pulse_ns(50000000, kInternalClockHz, p), 4095);  // saturates
  EXPECT_EQ(counts_for_pulse_ns(1500000, 26000000, p), 320);            // a board whose oscillator runs at 26 MHz
}

TEST(Pca9685Codec, StartSequenceSleepsSetsThePrescaleWakesAndRestarts) {
  Write w[5];
  ASSERT_EQ(start_sequence(121, true, w), 5u);
  EXPECT_EQ(bytes(w[0]), (std::vector<std::uint8_t>{0x00, 0x31}));  // MODE1: AI | SLEEP | ALLCALL
  EXPECT_EQ(bytes(w[1]), (std::vector<std::uint8_t>{0xfe, 0x79}));  // PRE_SCALE 121
  EXPECT_EQ(bytes(w[2]), (std::vector<std::uint8_t>{0x01, 0x04}));  // MODE2: totem pole
  EXPECT_EQ(bytes(w[3]), (std::vector<std::uint8_t>{0x00, 0x21}));  // awake
  EXPECT_EQ(w[3].wait_us, 500);                                     // the oscillator's start-up
  EXPECT_EQ(bytes(w[4]), (std::vector<std::uint8_t>{0x00, 0xa1}));  // RESTART
  ASSERT_EQ(start_sequence(121, false, w), 5u);
  EXPECT_EQ(bytes(w[2]), (std::vector<std::uint8_t>{0x01, 0x00}));  // open drain
}

TEST(Pca9685Codec, ChannelRegistersAndFullyOff) {
  EXPECT_EQ(bytes(channel_pulse(0, 307)), (std::vector<std::uint8_t>{0x06, 0x00, 0x00, 0x33, 0x01}));
  EXPECT_EQ(bytes(channel_pulse(15, 4095)), (std::vector<std::uint8_t>{0x42, 0x00, 0x00, 0xff, 0x0f}));
  EXPECT_EQ(bytes(channel_pulse(3, 9000)), (std::vector<std::uint8_t>{0x12, 0x00, 0x00, 0xff, 0x0f}));  // saturates
  EXPECT_EQ(bytes(channel_off(1)), (std::vector<std::uint8_t>{0x0a, 0x00, 0x00, 0x00, 0x10}));
  EXPECT_EQ(bytes(all_off()), (std::vector<std::uint8_t>{0xfa, 0x00, 0x00, 0x00, 0x10}));
}

TEST(Pca9685Codec, RegistersApplyWritesAsTheChipDoes) {
  Registers r;
  power_on(r);
  EXPECT_EQ(r.value[kMode1], 0x11);
  for (std::uint8_t c = 0; c < kChannels; ++c) EXPECT_EQ(pulse_counts(r, c), 0) << "fully off at power-on";
  Write start[5];
  for (std::size_t i = 0; i < start_sequence(121, true, start); ++i) ASSERT_TRUE(apply(r, start[i].bytes, start[i].length));
  EXPECT_EQ(r.value[kPreScale], 121);
  EXPECT_EQ(r.value[kMode1], 0xa1);
  // The data sheet's LED0 example: on at 409 (10 % delay), off at 1228 (20 % duty).
  const std::uint8_t led0[] = {0x06, 0x99, 0x01, 0xcc, 0x04};
  ASSERT_TRUE(apply(r, led0, sizeof led0));
  EXPECT_EQ(pulse_counts(r, 0), 1228 - 409);
  const Write w = channel_pulse(5, 307);
  ASSERT_TRUE(apply(r, w.bytes, w.length));
  EXPECT_EQ(pulse_counts(r, 5), 307);
  // Awake, the prescale ignores writes.
  const std::uint8_t prescale[] = {kPreScale, 30};
  ASSERT_TRUE(apply(r, prescale, sizeof prescale));
  EXPECT_EQ(r.value[kPreScale], 121);
  // Auto-increment wraps after LED15_OFF_H (69) to MODE1.
  const std::uint8_t wrap[] = {0x45, 0x00, 0xa1};
  ASSERT_TRUE(apply(r, wrap, sizeof wrap));
  EXPECT_EQ(r.value[kMode1], 0xa1);
  // ALL_LED fully off reaches every channel.
  const Write off = all_off();
  ASSERT_TRUE(apply(r, off.bytes, off.length));
  for (std::uint8_t c = 0; c < kChannels; ++c) EXPECT_EQ(pulse_counts(r, c), 0);
  EXPECT_FALSE(apply(r, wrap, 0));
}

}  // namespace
}  // namespace avar::firmware_iface::pca9685
