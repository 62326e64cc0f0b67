#pragma once
// Numbers in messages: the shortest form that reads naturally ("1.5", "30", "1e-06").
// Load-time only: allocates.

#include <string>

namespace avar {

std::string format_number(double value);

}  // namespace avar
