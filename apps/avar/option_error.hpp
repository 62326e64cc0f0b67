#pragma once
// A bad command-line value, reported like a file problem with the option as its place
// ("--band: found '5'; expected ...").

#include <string>

#include "avar/core/input_error.hpp"

namespace avar::app {

inline InputError option_error(const std::string& option, const std::string& problem) {
  return InputError({option, 0, 0}, problem);
}

}  // namespace avar::app
