#pragma once
// The NXP PCA9685 16-channel 12-bit PWM controller (hobby-servo boards on I2C), as pure functions
// from settings and pulse widths to the bytes of I2C write transactions, and a register file
// that applies them (what a simulated board does). One source for the host's I2C link and the
// device engine's players: freestanding C++14, <stdint.h> and <stddef.h> only, no allocation.
// Facts from the PCA9685 product data sheet (docs/protocols/pca9685.md).

#include <stddef.h>
#include <stdint.h>

namespace avar {
namespace firmware_iface {
namespace pca9685 {

const uint8_t kMode1 = 0x00;
const uint8_t kMode2 = 0x01;
const uint8_t kLed0OnL = 0x06;  ///< channel n's four registers start at 0x06 + 4n
const uint8_t kAllLedOnL = 0xfa;
const uint8_t kPreScale = 0xfe;

// MODE1 bits.
const uint8_t kRestart = 0x80;
const uint8_t kExtClk = 0x40;
const uint8_t kAutoIncrement = 0x20;
const uint8_t kSleep = 0x10;
const uint8_t kAllCall = 0x01;
// MODE2 bits.
const uint8_t kInvert = 0x10;
const uint8_t kOutDrv = 0x04;  ///< totem-pole outputs (the boards' default); open drain without
/// LEDn_ON_H / LEDn_OFF_H bit 4: the output fully on / fully off.
const uint8_t kFullBit = 0x10;

const uint32_t kInternalClockHz = 25000000;
const uint8_t kMinPreScale = 3;  ///< the hardware's floor: 1526 Hz at 25 MHz
const uint8_t kChannels = 16;
const uint16_t kCounts = 4096;  ///< one PWM period

/// The data sheet's prescale for an output frequency: round(clock / (4096 * hz)) - 1, within 3..255.
uint8_t prescale_for(uint32_t clock_hz, uint32_t hz);
/// The output frequency a prescale gives, in mHz: clock / (4096 * (prescale + 1)).
uint32_t frequency_mhz(uint32_t clock_hz, uint8_t prescale);
/// A pulse of `pulse_ns` nanoseconds in counts of the period (rounded), saturated to 0..4095.
uint16_t counts_for_pulse_ns(uint32_t pulse_ns, uint32_t clock_hz, uint8_t prescale);

/// One register write transaction: the register, then its data (auto-increment for more bytes).
struct Write {
  uint8_t bytes[5];
  uint8_t length;
  uint16_t wait_us;  ///< to wait after it (the oscillator's start-up)
};

/// The start-up: sleep (auto-increment on, all-call kept), the prescale (writable only asleep),
/// MODE2 (totem-pole or open-drain outputs), wake, wait 500 us for the oscillator, restart. Fills
/// `out` (5 writes) and returns how many.
size_t start_sequence(uint8_t prescale, bool totem_pole, Write* out);
/// Channel `channel`'s output high from count 0 to `off` (0..4095): the four LEDn registers.
Write channel_pulse(uint8_t channel, uint16_t off);
/// Channel `channel` fully off (a servo that receives no pulse goes limp).
Write channel_off(uint8_t channel);
/// Every channel fully off at once (ALL_LED registers): the board's safe state.
Write all_off();

/// A PCA9685's registers, as the chip keeps them: what a simulated board or a test reads.
struct Registers {
  uint8_t value[256];
};
/// Power-on values: MODE1 0x11 (asleep, all-call), MODE2 0x04, every output fully off, prescale 0x1e.
void power_on(Registers& r);
/// Applies one write transaction (register then data) as the chip does: auto-increment when
/// MODE1 says so (past register 69 to MODE1, from 250 through 254 then to MODE1), the prescale
/// only while asleep, ALL_LED writes into every channel. Returns false for an empty transaction.
bool apply(Registers& r, const uint8_t* bytes, size_t length);
/// Channel `channel`'s pulse width in counts as the registers define it (0 fully off, 4096 fully
/// on; otherwise off - on modulo 4096).
uint16_t pulse_counts(const Registers& r, uint8_t channel);

}  // namespace pca9685
}  // namespace firmware_iface
}  // namespace avar
