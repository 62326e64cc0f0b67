#pragma once
// Errors in user input (rig, show and other files, command-line values). Thrown only at load
// and configuration time, never inside the tick.

#include <stdexcept>
#include <cstddef>
#include <string>
#include <string_view>

namespace avar {

/// Where in a text input something was found. line and column are 1-based; 0 means unknown.
struct SourceLocation {
  std::string file;
  int line = 0;
  int column = 0;
};

/// "file:line:column" (parts that are unknown are left out).
std::string to_string(const SourceLocation& where);

/// Where byte `offset` of `text` (the whole file) is: 1-based line and column (in bytes).
SourceLocation location_at(std::string file, std::string_view text, std::size_t offset);

/// A problem in user input. what() is one line: "<where>: <problem>", where the problem says
/// what was found and what was expected.
class InputError : public std::runtime_error {
 public:
  InputError(SourceLocation where, const std::string& problem);
  const SourceLocation& where() const noexcept { return where_; }
  const std::string& problem() const noexcept { return problem_; }

 private:
  SourceLocation where_;
  std::string problem_;
};

}  // namespace avar
