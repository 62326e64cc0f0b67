#pragma once
// Reading one number of a settings block within its range, as every protocol schema does.
// Load-time only; failures are InputErrors at the value.

#include <string>

#include "avar/core/format.hpp"
#include "avar/core/scalar_value.hpp"

namespace avar::rig {

/// The value as a number from low to high (`unit` for the message, may be empty).
inline double number_in(const ScalarValue& v, const std::string& key, double low, double high, const std::string& unit = "") {
  const double x = v.as_double(key);
  if (x < low || x > high)
    v.fail("expected " + key + " from " + format_number(low) + " to " + format_number(high) + (unit.empty() ? "" : " " + unit) +
           ", found " + v.describe());
  return x;
}

/// The value as a whole number from low to high.
inline long long integer_in(const ScalarValue& v, const std::string& key, long long low, long long high,
                            const std::string& unit = "") {
  const long long x = v.as_integer(key);
  if (x < low || x > high)
    v.fail("expected " + key + " from " + std::to_string(low) + " to " + std::to_string(high) + (unit.empty() ? "" : " " + unit) +
           ", found " + v.describe());
  return x;
}

}  // namespace avar::rig
