#include "avar/core/format.hpp"

#include <sstream>

namespace avar {

std::string format_number(double value) {
  std::ostringstream s;
  s << value;
  return s.str();
}

}  // namespace avar
