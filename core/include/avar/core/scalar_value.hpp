#pragma once
// One value read from a text input (a YAML scalar, a setting), with where it was found, and the
// conversions every input reader shares: each fails with an InputError naming the place, what
// was found and what was expected. Load-time only.

#include <string>
#include <string_view>

#include "avar/core/input_error.hpp"

namespace avar {

struct ScalarValue {
  std::string text;    ///< the scalar's text (empty when not a scalar)
  bool scalar = true;  ///< false: a map, a list or nothing was found instead
  std::string found;   ///< how to name what was found in messages: "'abc'", "a map", "nothing"
  SourceLocation where;

  /// A scalar with its text quoted for messages.
  static ScalarValue of_text(std::string text, SourceLocation where);

  [[noreturn]] void fail(const std::string& problem) const;
  const std::string& describe() const { return found; }

  double as_double(std::string_view what) const;       ///< finite number
  long long as_integer(std::string_view what) const;   ///< whole number (decimal, or hexadecimal as 0x7F0)
  bool as_bool(std::string_view what) const;           ///< true / false (yes/no, on/off)
  std::string as_string(std::string_view what) const;  ///< non-empty scalar
};

}  // namespace avar
