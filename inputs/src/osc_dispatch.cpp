#include "avar/inputs/osc_dispatch.hpp"

#include <algorithm>
#include <cmath>

namespace avar::inputs {
namespace {

bool name_character(char c) noexcept {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '.' || c == '-';
}

bool valid_name(std::string_view name) noexcept {
  return !name.empty() && name.size() <= kMaxOscControlName && std::all_of(name.begin(), name.end(), name_character);
}

/// The single numeric argument's value, or nullopt.
std::optional<double> single_number(std::string_view types, std::span<const double> values) noexcept {
  if (types.size() != 1 || values.size() != 1) return std::nullopt;
  switch (types[0]) {
    case 'f':
    case 'd':
    case 'i':
    case 'h':
      if (!std::isfinite(values[0])) return std::nullopt;
      return values[0];
    case 'T': return 1.0;
    case 'F': return 0.0;
    default: return std::nullopt;
  }
}

}  // namespace

std::optional<OscControl> osc_control(std::string_view path, std::string_view types, std::span<const double> values) noexcept {
  std::string_view control;
  if (path.starts_with(kOscControlPrefix)) {
    control = path.substr(kOscControlPrefix.size());
    if (!valid_name(control)) return std::nullopt;
  } else if (path.starts_with(kOscChannelPrefix)) {
    if (!valid_name(path.substr(kOscChannelPrefix.size()))) return std::nullopt;
    // "/avar/channel/jaw" -> "channel/jaw", a suffix of the path.
    control = path.substr(kOscChannelPrefix.size() - kOscChannelControlPrefix.size());
  } else {
    return std::nullopt;
  }
  const std::optional<double> value = single_number(types, values);
  if (!value) return std::nullopt;
  return OscControl{control, *value};
}

}  // namespace avar::inputs
