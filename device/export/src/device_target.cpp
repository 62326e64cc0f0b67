#include "avar/device/device_target.hpp"

#include <array>
#include <string>

namespace avar::device {
namespace {

constexpr std::size_t kKiB = 1024;

// Measured 2026-12-07 (see the header): engine figures are the linked size of the engine, figure
// and codec rounded up; channel RAM is sizeof(PlayerChannel) + sizeof(FigureOutput) on the target.
// A streaming board's: the linked size of the streaming player, the avar-device codec, the limiter
// and the figure's outputs, rounded up; sizeof(StreamPlayer) and StreamFigure's own fields (the
// parser's buffer and an answer's room depend on the channels: stream_export.cpp adds them);
// sizeof(StreamChannel) + sizeof(FigureOutput).
constexpr DeviceTarget avr(std::string_view name, std::string_view boards, std::string_view i2c_pins, std::size_t flash,
                           std::size_t ram, std::size_t engine, int pin_high, std::size_t pin_servos, int sda, int scl) {
  DeviceTarget t;
  t.name = name;
  t.boards = boards;
  t.architecture = "avr";
  t.platformio = "atmelavr";
  t.i2c_pins = i2c_pins;
  t.flash = flash;
  t.ram = ram;
  t.data_limit = 65536 - 512;  // the vectors and the runtime's own tables come first
  t.core_flash = 4608;
  t.core_ram = 448 + 320;  // Serial and Wire buffers; a stack reserve (the engine's 64-bit arithmetic)
  t.engine_flash = engine;
  t.easings_flash = 10752;
  t.cycles_flash = 1792;
  t.extrapolation_flash = 1024;
  t.fast_flash = 1280;
  t.channel_ram = 145;
  t.easings_channel_ram = 48;
  t.cycles_channel_ram = 18;
  t.extrapolation_channel_ram = 16;
  t.figure_ram = 33;
  t.board_ram = 7;
  t.show_ram = 6;
  t.stream_flash = 15104;
  t.stream_ram = 54;
  t.stream_channel_ram = 42;
  // The AVR core's Servo library: Timer1 (and 3, 4, 5 on a Mega), 12 servos a timer, 3 bytes each.
  t.pin_high = pin_high;
  t.pin_servos = pin_servos;
  t.serial_pins = {0, 1};
  t.i2c_pin_numbers = {sda, scl};
  t.servo_flash = 1792;  // and the figure's pin outputs (AVAR_DEVICE_PINS): 390 bytes measured
  t.servo_ram = 3 * pin_servos + 8;
  t.servo_each_ram = 4;
  return t;
}

constexpr DeviceTarget arm(std::string_view name, std::string_view boards, std::string_view architecture,
                           std::string_view platformio, std::string_view i2c_pins, std::size_t flash, std::size_t ram,
                           std::size_t core_flash, std::size_t core_ram, bool m0) {
  DeviceTarget t;
  t.name = name;
  t.boards = boards;
  t.architecture = architecture;
  t.platformio = platformio;
  t.i2c_pins = i2c_pins;
  t.flash = flash;
  t.ram = ram;
  t.data_limit = flash;
  t.core_flash = core_flash;
  t.core_ram = core_ram;
  t.engine_flash = m0 ? 8704 : 7680;
  t.easings_flash = m0 ? 3328 : 3072;
  t.cycles_flash = 640;
  t.extrapolation_flash = m0 ? 512 : 384;
  t.fast_flash = 320;
  t.channel_ram = 168;
  t.easings_channel_ram = 48;
  t.cycles_channel_ram = 24;
  t.extrapolation_channel_ram = 24;
  t.figure_ram = 56;
  t.board_ram = 8;
  t.show_ram = 8;
  t.stream_flash = m0 ? 7680 : 6400;
  t.stream_ram = 84;
  t.stream_channel_ram = 64;
  t.servo_flash = 2560;
  t.servo_ram = 128;
  t.servo_each_ram = 16;
  return t;
}

/// A Linux machine (a Raspberry Pi): the exported program, built by the project's CMakeLists.txt.
DeviceTarget linux_host() {
  DeviceTarget t = arm("host", "Linux (a Raspberry Pi or any PC with PCA9685 boards on /dev/i2c-N)", "*", "native",
                       "the bus's SDA and SCL (a Raspberry Pi: GPIO 2 and 3, /dev/i2c-1)", std::size_t{1} << 30,
                       std::size_t{1} << 30, 0, 0, false);
  t.data_limit = t.flash;
  return t;
}

const std::array<DeviceTarget, 7> kTargets = {
    avr("atmega328p", "Arduino Uno, Nano, Pro Mini (16 MHz)", "SDA A4, SCL A5", 32 * kKiB - 512, 2048, 20480, 19, 12, 18, 19),
    avr("atmega2560", "Arduino Mega 2560", "SDA 20, SCL 21", 256 * kKiB - 8 * kKiB, 8192, 20608, 69, 48, 20, 21),
    [] {
      // arduino-pico's Servo runs each servo on a PIO state machine: 8 of them; Serial is USB.
      DeviceTarget t = arm("cortex-m0plus", "Raspberry Pi Pico (RP2040; the arduino-pico core)", "rp2040", "raspberrypi",
                           "SDA GP4, SCL GP5", 2048 * kKiB - 64 * kKiB, 264 * kKiB, 96 * kKiB, 16 * kKiB, true);
      t.pin_high = 28;
      t.pin_servos = 8;
      t.i2c_pin_numbers = {4, 5};
      return t;
    }(),
    [] {
      // STM32duino's Servo: one timer, 12 servos; pins by the core's numbers (the variant's PA0...).
      DeviceTarget t = arm("cortex-m3", "STM32F103C8 (Blue Pill; the STM32duino core)", "stm32", "ststm32", "SDA PB7, SCL PB6",
                           64 * kKiB, 20 * kKiB, 24 * kKiB, 3 * kKiB, false);
      t.pin_high = 47;
      t.pin_servos = 12;
      return t;
    }(),
    [] {
      DeviceTarget t = arm("cortex-m4", "STM32F411CE (Black Pill; the STM32duino core)", "stm32", "ststm32", "SDA PB7, SCL PB6",
                           512 * kKiB, 128 * kKiB, 32 * kKiB, 4 * kKiB, false);
      t.pin_high = 47;
      t.pin_servos = 12;
      return t;
    }(),
    [] {
      // RISC-V: no compiler here to measure with; the ARM figures doubled, and the ESP32 core's
      // own size (its Wi-Fi libraries are not linked by this sketch).
      DeviceTarget t = arm("esp32c3", "ESP32-C3 boards (the arduino-esp32 core)", "esp32", "espressif32", "SDA 8, SCL 9",
                           1280 * kKiB, 320 * kKiB, 256 * kKiB, 48 * kKiB, false);
      t.engine_flash *= 2;
      t.easings_flash *= 2;
      t.cycles_flash *= 2;
      t.extrapolation_flash *= 2;
      t.fast_flash *= 2;
      t.stream_flash *= 2;
      // ESP32Servo on the C3's 6 LEDC channels; UART0 on 20 and 21.
      t.servo_flash *= 2;
      t.pin_high = 21;
      t.pin_servos = 6;
      t.serial_pins = {20, 21};
      t.i2c_pin_numbers = {8, 9};
      return t;
    }(),
    linux_host(),
};

}  // namespace

std::size_t DeviceTarget::engine_flash_for(std::uint8_t features, bool fast) const noexcept {
  return engine_flash - (fast ? 0 : fast_flash) + (features & kFeatureEasings ? easings_flash : 0) +
         (features & kFeatureCycles ? cycles_flash : 0) + (features & kFeatureExtrapolation ? extrapolation_flash : 0);
}

std::size_t DeviceTarget::channel_ram_for(std::uint8_t features) const noexcept {
  return channel_ram + (features & kFeatureEasings ? easings_channel_ram : 0) +
         (features & kFeatureCycles ? cycles_channel_ram : 0) +
         (features & kFeatureExtrapolation ? extrapolation_channel_ram : 0);
}

std::span<const DeviceTarget> device_targets() { return kTargets; }

const DeviceTarget* find_device_target(std::string_view name) {
  for (const DeviceTarget& t : kTargets)
    if (t.name == name) return &t;
  return nullptr;
}

std::string device_target_names() {
  std::string names;
  for (const DeviceTarget& t : kTargets) names += (names.empty() ? "" : ", ") + std::string(t.name);
  return names;
}

}  // namespace avar::device
