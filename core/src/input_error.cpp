#include "avar/core/input_error.hpp"

namespace avar {

std::string to_string(const SourceLocation& where) {
  std::string out = where.file.empty() ? std::string("<input>") : where.file;
  if (where.line > 0) {
    out += ':' + std::to_string(where.line);
    if (where.column > 0) out += ':' + std::to_string(where.column);
  }
  return out;
}

InputError::InputError(SourceLocation where, const std::string& problem)
    : std::runtime_error(to_string(where) + ": " + problem), where_(std::move(where)), problem_(problem) {}

}  // namespace avar
