// The Maestro codec's host part (maestro_codec.hpp's C++20 section): unit conversions in double
// and the error register's names.
#include "avar/firmware_iface/maestro_codec.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <string>

namespace avar::firmware_iface::maestro {

std::string describe_errors(std::uint16_t errors) {
  static constexpr const char* kNames[] = {"serial signal error", "serial overrun error",    "serial RX buffer full",
                                           "serial CRC error",    "serial protocol error",   "serial timeout",
                                           "script stack error",  "script call stack error", "script program counter error"};
  std::string out;
  for (unsigned bit = 0; bit < 16; ++bit) {
    if (!(errors & (1u << bit))) continue;
    if (!out.empty()) out += ", ";
    out += bit < std::size(kNames) ? kNames[bit] : "error bit " + std::to_string(bit);
  }
  return out.empty() ? "none" : out;
}

std::uint16_t quarter_us_from_us(double us) noexcept {
  if (!(us > 0)) return 0;
  // Clamp before rounding: lround of a value beyond `long` (or of infinity) is undefined.
  return static_cast<std::uint16_t>(std::lround(std::min(us * 4.0, static_cast<double>(kMaxValue))));
}

double us_from_quarter_us(std::uint16_t quarter_us) noexcept { return quarter_us / 4.0; }

std::uint16_t speed_units_from_us_per_s(double us_per_s) noexcept {
  // 1 unit = 0.25 µs per 10 ms = 25 µs/s; round down so the device is never faster than asked,
  // but never to 0, which would mean "unlimited".
  if (!(us_per_s > 0)) return 1;
  return static_cast<std::uint16_t>(std::clamp(std::floor(us_per_s / 25.0), 1.0, static_cast<double>(kMaxValue)));
}

std::uint16_t acceleration_units_from_us_per_s2(double us_per_s2) noexcept {
  if (!(us_per_s2 > 0)) return 1;
  return static_cast<std::uint16_t>(std::clamp(std::floor(us_per_s2 / 312.5), 1.0, static_cast<double>(kMaxAcceleration)));
}

double us_per_s_from_speed_units(std::uint16_t speed) noexcept { return 25.0 * speed; }
double us_per_s2_from_acceleration_units(std::uint16_t acceleration) noexcept { return 312.5 * acceleration; }

}  // namespace avar::firmware_iface::maestro
