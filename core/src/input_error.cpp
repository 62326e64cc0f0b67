#include "avar/core/input_error.hpp"

#include <algorithm>
#include <utility>

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

SourceLocation location_at(std::string file, std::string_view text, std::size_t offset) {
  offset = std::min(offset, text.size());
  int line = 1;
  std::size_t line_start = 0;
  for (std::size_t i = 0; i < offset; ++i) {
    if (text[i] == '\n') {
      ++line;
      line_start = i + 1;
    }
  }
  return {std::move(file), line, static_cast<int>(offset - line_start) + 1};
}

}  // namespace avar
