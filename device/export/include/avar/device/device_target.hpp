#pragma once
// The microcontrollers avar exports to, with what they offer a sketch and what the exported
// player costs on each: the numbers an export's fit check adds up. Engine and RAM figures were
// measured by building the engine and the figure for each target (avr-g++ 5.4 -Os, arm-none-eabi-g++
// 12 -Os, sections collected) and are checked against a fresh build by a test where the compiler is
// present; the Arduino core's share (Serial, Wire, the loop) is an estimate with margin.

#include <array>
#include <cstddef>
#include <span>
#include <string_view>

#include "avar/device/show_image.hpp"

namespace avar::device {

struct DeviceTarget {
  std::string_view name;          ///< what --target takes
  std::string_view boards;        ///< boards of this kind, for messages and docs
  std::string_view architecture;  ///< library.properties' architectures
  std::string_view platformio;    ///< library.json's platforms
  std::string_view i2c_pins;      ///< where a PCA9685 board's SDA and SCL go
  std::size_t flash = 0;          ///< program flash a sketch may use (bytes, the bootloader's taken off)
  std::size_t ram = 0;            ///< RAM (bytes)
  /// Flash for data read in place: on AVR pgm_read_byte reaches the first 64 KiB only.
  std::size_t data_limit = 0;
  std::size_t core_flash = 0;  ///< the Arduino core with Serial and Wire, and the sketch's glue
  std::size_t core_ram = 0;    ///< their buffers and state, and a reserve for the stack
  /// The engine, the limiter, the player, the figure and the PCA9685 codec with nothing but
  /// steps, lines and cubics and the 32-bit fast path; what each feature adds, and what the fast
  /// path takes (config.hpp).
  std::size_t engine_flash = 0, easings_flash = 0, cycles_flash = 0, extrapolation_flash = 0, fast_flash = 0;
  /// RAM per channel (PlayerChannel and FigureOutput), and what each feature adds to it.
  std::size_t channel_ram = 0, easings_channel_ram = 0, cycles_channel_ram = 0, extrapolation_channel_ram = 0;
  std::size_t figure_ram = 0;  ///< the Figure and player themselves
  std::size_t board_ram = 0;   ///< per PCA9685 board
  std::size_t show_ram = 0;    ///< per show (its PlayerShow entry)
  /// A streaming board: the streaming player, the avar-device codec, the limiter and the figure's
  /// outputs; the player with its frame parser and an answer's room; RAM per channel
  /// (StreamChannel and FigureOutput). Knot frames take 4 + 4 bytes per channel each.
  std::size_t stream_flash = 0, stream_ram = 0, stream_channel_ram = 0;
  /// Servos on the board's own pins (the core's Servo library): the highest pin number (-1: no
  /// servos on pins), how many servos the library drives, the pins that carry Serial and I2C (-1:
  /// none fixed), and what the library costs (estimates): flash, RAM, RAM per servo.
  int pin_high = -1;
  std::size_t pin_servos = 0;
  std::array<int, 2> serial_pins{-1, -1}, i2c_pin_numbers{-1, -1};
  std::size_t servo_flash = 0, servo_ram = 0, servo_each_ram = 0;

  /// The Linux host: a program built with CMake, not an Arduino library.
  bool host() const noexcept { return name == "host"; }

  std::size_t engine_flash_for(std::uint8_t features, bool fast) const noexcept;
  std::size_t channel_ram_for(std::uint8_t features) const noexcept;
};

/// Every target, in the order --help lists them.
std::span<const DeviceTarget> device_targets();
/// The target named `name`, or nullptr.
const DeviceTarget* find_device_target(std::string_view name);
/// "atmega328p, atmega2560, ...": for messages.
std::string device_target_names();

}  // namespace avar::device
