#include "avar/core/scalar_value.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace avar {

ScalarValue ScalarValue::of_text(std::string text, SourceLocation where) {
  ScalarValue v;
  v.found = "'" + text + "'";
  v.text = std::move(text);
  v.where = std::move(where);
  return v;
}

void ScalarValue::fail(const std::string& problem) const { throw InputError(where, problem); }

double ScalarValue::as_double(std::string_view what) const {
  if (!scalar) fail("expected " + std::string(what) + " to be a number, found " + found);
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(v))
    fail("expected " + std::string(what) + " to be a finite number, found " + found);
  return v;
}

long long ScalarValue::as_integer(std::string_view what) const {
  if (!scalar) fail("expected " + std::string(what) + " to be a whole number, found " + found);
  char* end = nullptr;
  errno = 0;
  // YAML 1.2 writes hexadecimal as 0x..: CAN identifiers read naturally so.
  const bool hex = text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X');
  const long long v = std::strtoll(text.c_str() + (hex ? 2 : 0), &end, hex ? 16 : 10);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE)
    fail("expected " + std::string(what) + " to be a whole number, found " + found);
  return v;
}

bool ScalarValue::as_bool(std::string_view what) const {
  if (scalar) {
    if (text == "true" || text == "yes" || text == "on") return true;
    if (text == "false" || text == "no" || text == "off") return false;
  }
  fail("expected " + std::string(what) + " to be true or false, found " + found);
}

std::string ScalarValue::as_string(std::string_view what) const {
  if (!scalar || text.empty()) fail("expected " + std::string(what) + " to be a name, found " + found);
  return text;
}

}  // namespace avar
