#pragma once
// Numbers in messages and reports: the shortest form that reads naturally ("1.5", "30",
// "1e-06"), or a fixed number of decimals.
// Load-time only: allocates.

#include <string>

namespace avar {

std::string format_number(double value);

/// Fixed-point text with `decimals` digits after the point, whatever the locale; a value that
/// rounds to zero has no minus sign ("0.00", not "-0.00").
std::string format_fixed(double value, int decimals);

/// Appends the shortest decimal text that reads back to the same double (CSV output); -0 is
/// written as 0.
void append_round_trip(std::string& text, double value);

}  // namespace avar
