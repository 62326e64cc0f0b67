#include "avar/core/format.hpp"

#include <array>
#include <charconv>
#include <cstdio>
#include <sstream>

namespace avar {

std::string format_number(double value) {
  std::ostringstream s;
  s << value;
  return s.str();
}

std::string format_fixed(double value, int decimals) {
  std::array<char, 64> buf{};
#ifdef __EMSCRIPTEN__
  // emscripten 3.1.6's libc++ has no floating-point to_chars (the studio page's curve engine).
  std::string s(buf.data(), static_cast<std::size_t>(std::snprintf(buf.data(), buf.size(), "%.*f", decimals, value)));
#else
  const auto result = std::to_chars(buf.data(), buf.data() + buf.size(), value, std::chars_format::fixed, decimals);
  std::string s(buf.data(), result.ptr);
#endif
  if (s.find_first_not_of("-0.") == std::string::npos)
    s = decimals > 0 ? "0." + std::string(static_cast<std::size_t>(decimals), '0') : "0";
  return s;
}

void append_round_trip(std::string& text, double value) {
  if (value == 0) value = 0;
  std::array<char, 32> buf{};
#ifdef __EMSCRIPTEN__
  // Reads back to the same double, though not always in the fewest digits.
  text.append(buf.data(), static_cast<std::size_t>(std::snprintf(buf.data(), buf.size(), "%.17g", value)));
#else
  const auto result = std::to_chars(buf.data(), buf.data() + buf.size(), value);
  text.append(buf.data(), result.ptr);
#endif
}

}  // namespace avar
