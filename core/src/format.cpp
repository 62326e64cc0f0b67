#include "avar/core/format.hpp"

#include <array>
#include <charconv>
#include <sstream>

namespace avar {

std::string format_number(double value) {
  std::ostringstream s;
  s << value;
  return s.str();
}

std::string format_fixed(double value, int decimals) {
  std::array<char, 64> buf{};
  const auto result = std::to_chars(buf.data(), buf.data() + buf.size(), value, std::chars_format::fixed, decimals);
  std::string s(buf.data(), result.ptr);
  if (s.find_first_not_of("-0.") == std::string::npos) s = decimals > 0 ? "0." + std::string(static_cast<std::size_t>(decimals), '0') : "0";
  return s;
}

void append_round_trip(std::string& text, double value) {
  if (value == 0) value = 0;
  std::array<char, 32> buf{};
  const auto result = std::to_chars(buf.data(), buf.data() + buf.size(), value);
  text.append(buf.data(), result.ptr);
}

}  // namespace avar
