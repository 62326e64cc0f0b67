#pragma once
// Helpers for reading avar's YAML files (rigs, shows) with yaml-cpp so that every error names
// file, line and column, what was found and what was expected. Load-time only; throws InputError.

#include <yaml-cpp/yaml.h>

#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "avar/core/input_error.hpp"
#include "avar/core/scalar_value.hpp"

namespace avar::config {

/// Parses a whole YAML file. Throws InputError for a missing file or malformed YAML.
YAML::Node load_yaml_file(const std::string& path);
/// The same from the text of a document; `path` names it in errors.
YAML::Node parse_yaml_text(const std::string& text, const std::string& path);

/// A node together with the file it came from, so that errors can point at it.
struct YamlRef {
  YAML::Node node;
  const std::string* file;  ///< path of the file; outlives the ref

  SourceLocation where() const;
  [[noreturn]] void fail(const std::string& problem) const;

  bool is_map() const { return node.IsMap(); }
  bool is_sequence() const { return node.IsSequence(); }
  /// The node must be a map / sequence; `what` names it in the error ("the rig file", "a key").
  void expect_map(std::string_view what) const;
  void expect_sequence(std::string_view what) const;
  /// Fails if the map has a key not in `allowed` (catches typos such as "interpolaton").
  void expect_only_keys(std::span<const std::string_view> allowed, std::string_view what) const;
  void expect_only_keys(std::initializer_list<std::string_view> allowed, std::string_view what) const {
    expect_only_keys(std::span<const std::string_view>(allowed.begin(), allowed.size()), what);
  }

  bool has(std::string_view key) const;
  /// The child at `key`; fails naming the map when it is missing.
  YamlRef at(std::string_view key, std::string_view what) const;
  std::optional<YamlRef> find(std::string_view key) const;
  YamlRef operator[](std::size_t index) const;
  std::size_t size() const { return node.size(); }

  /// The node as a scalar value with its place (ScalarValue::scalar is false for maps, lists).
  ScalarValue scalar() const;
  /// Scalar conversions (ScalarValue's); each fails with what was found and what was expected.
  double as_double(std::string_view what) const;       ///< finite number
  long long as_integer(std::string_view what) const;   ///< whole number
  bool as_bool(std::string_view what) const;           ///< true / false
  std::string as_string(std::string_view what) const;  ///< non-empty scalar

  /// The found value, quoted for error messages ("'abc'", "a map", "a list").
  std::string describe() const;
};

}  // namespace avar::config
