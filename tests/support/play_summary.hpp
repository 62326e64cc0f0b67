#pragma once
// Reading `avar play`'s printed summary in tests.

#include <map>
#include <sstream>
#include <string>

namespace avar::testing {

/// The summary's max err per channel (rows whose unit is deg or %), by channel name.
inline std::map<std::string, double> max_errors(const std::string& out) {
  std::map<std::string, double> errors;
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream row(line);
    std::string name, unit;
    double max_err = 0;
    if (row >> name >> unit >> max_err && (unit == "deg" || unit == "%")) errors[name] = max_err;
  }
  return errors;
}

}  // namespace avar::testing
