#include "avar/firmware_iface/pca9685_codec.hpp"

namespace avar {
namespace firmware_iface {
namespace pca9685 {

uint8_t prescale_for(uint32_t clock_hz, uint32_t hz) {
  if (hz == 0) return 255;
  const uint64_t divisor = static_cast<uint64_t>(kCounts) * hz;
  const uint64_t rounded = (clock_hz + divisor / 2) / divisor;
  if (rounded <= kMinPreScale + 1u) return kMinPreScale;
  if (rounded > 256u) return 255;
  return static_cast<uint8_t>(rounded - 1);
}

uint32_t frequency_mhz(uint32_t clock_hz, uint8_t prescale) {
  const uint64_t divisor = static_cast<uint64_t>(kCounts) * (prescale + 1u);
  return static_cast<uint32_t>((static_cast<uint64_t>(clock_hz) * 1000u + divisor / 2) / divisor);
}

uint16_t counts_for_pulse_ns(uint32_t pulse_ns, uint32_t clock_hz, uint8_t prescale) {
  // One count lasts (prescale + 1) / clock seconds.
  const uint64_t per_count_scaled = static_cast<uint64_t>(prescale + 1u) * 1000000000u;  // ns * clock
  const uint64_t counts = (static_cast<uint64_t>(pulse_ns) * clock_hz + per_count_scaled / 2) / per_count_scaled;
  return static_cast<uint16_t>(counts > 4095u ? 4095u : counts);
}

namespace {

Write write2(uint8_t reg, uint8_t value, uint16_t wait_us) {
  Write w = {{reg, value, 0, 0, 0}, 2, wait_us};
  return w;
}

Write write5(uint8_t reg, uint8_t on_l, uint8_t on_h, uint8_t off_l, uint8_t off_h) {
  Write w = {{reg, on_l, on_h, off_l, off_h}, 5, 0};
  return w;
}

uint8_t channel_register(uint8_t channel) { return static_cast<uint8_t>(kLed0OnL + 4u * (channel & 0x0fu)); }

}  // namespace

size_t start_sequence(uint8_t prescale, bool totem_pole, Write* out) {
  if (prescale < kMinPreScale) prescale = kMinPreScale;
  const uint8_t awake = kAutoIncrement | kAllCall;
  out[0] = write2(kMode1, static_cast<uint8_t>(awake | kSleep), 0);
  out[1] = write2(kPreScale, prescale, 0);
  out[2] = write2(kMode2, totem_pole ? kOutDrv : 0, 0);
  out[3] = write2(kMode1, awake, 500);
  out[4] = write2(kMode1, static_cast<uint8_t>(awake | kRestart), 0);
  return 5;
}

Write channel_pulse(uint8_t channel, uint16_t off) {
  if (off > 4095u) off = 4095u;
  return write5(channel_register(channel), 0, 0, static_cast<uint8_t>(off & 0xffu), static_cast<uint8_t>(off >> 8));
}

Write channel_off(uint8_t channel) { return write5(channel_register(channel), 0, 0, 0, kFullBit); }

Write all_off() { return write5(kAllLedOnL, 0, 0, 0, kFullBit); }

void power_on(Registers& r) {
  for (unsigned i = 0; i < 256; ++i) r.value[i] = 0;
  r.value[kMode1] = kSleep | kAllCall;
  r.value[kMode2] = kOutDrv;
  for (uint8_t c = 0; c < kChannels; ++c) r.value[channel_register(c) + 3] = kFullBit;
  r.value[kAllLedOnL + 1] = kFullBit;
  r.value[kAllLedOnL + 3] = kFullBit;
  r.value[kPreScale] = 0x1e;
}

namespace {

void store(Registers& r, uint8_t reg, uint8_t value) {
  if (reg == kPreScale) {
    if (r.value[kMode1] & kSleep) r.value[kPreScale] = value < kMinPreScale ? kMinPreScale : value;
    return;
  }
  if (reg >= kAllLedOnL && reg < kPreScale) {
    // ALL_LED_ON_L .. ALL_LED_OFF_H: the same byte of every channel.
    for (uint8_t c = 0; c < kChannels; ++c) r.value[channel_register(c) + (reg - kAllLedOnL)] = value;
  }
  r.value[reg] = value;
}

uint8_t next_register(uint8_t reg) {
  if (reg == 69 || reg == 254) return kMode1;
  return static_cast<uint8_t>(reg + 1u);
}

}  // namespace

bool apply(Registers& r, const uint8_t* bytes, size_t length) {
  if (length == 0) return false;
  uint8_t reg = bytes[0];
  for (size_t i = 1; i < length; ++i) {
    store(r, reg, bytes[i]);
    if (r.value[kMode1] & kAutoIncrement) reg = next_register(reg);
  }
  return true;
}

uint16_t pulse_counts(const Registers& r, uint8_t channel) {
  const uint8_t base = channel_register(channel);
  const uint8_t on_h = r.value[base + 1], off_h = r.value[base + 3];
  if (off_h & kFullBit) return 0;
  if (on_h & kFullBit) return kCounts;
  const uint16_t on = static_cast<uint16_t>(r.value[base] | ((on_h & 0x0fu) << 8));
  const uint16_t off = static_cast<uint16_t>(r.value[base + 2] | ((off_h & 0x0fu) << 8));
  return static_cast<uint16_t>((off - on) & 0x0fffu);
}

}  // namespace pca9685
}  // namespace firmware_iface
}  // namespace avar
