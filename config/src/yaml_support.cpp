#include "yaml_support.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

namespace avar::config {

YAML::Node load_yaml_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError({path, 0, 0}, std::string("cannot read file: ") + std::strerror(errno));
  std::stringstream text;
  text << in.rdbuf();
  return parse_yaml_text(text.str(), path);
}

YAML::Node parse_yaml_text(const std::string& text, const std::string& path) {
  try {
    YAML::Node root = YAML::Load(text);
    if (!root || root.IsNull()) throw InputError({path, 1, 1}, "the file is empty; expected a YAML map");
    return root;
  } catch (const YAML::Exception& e) {
    throw InputError({path, e.mark.line + 1, e.mark.column + 1}, "malformed YAML: " + e.msg);
  }
}

SourceLocation YamlRef::where() const {
  const YAML::Mark m = node.Mark();
  if (m.is_null()) return {*file, 0, 0};
  return {*file, m.line + 1, m.column + 1};
}

void YamlRef::fail(const std::string& problem) const { throw InputError(where(), problem); }

std::string YamlRef::describe() const {
  if (!node || node.IsNull()) return "nothing";
  if (node.IsMap()) return "a map";
  if (node.IsSequence()) return "a list";
  return "'" + node.Scalar() + "'";
}

void YamlRef::expect_map(std::string_view what) const {
  if (!node.IsMap()) fail("expected " + std::string(what) + " to be a map of 'key: value', found " + describe());
}

void YamlRef::expect_sequence(std::string_view what) const {
  if (!node.IsSequence()) fail("expected " + std::string(what) + " to be a list, found " + describe());
}

void YamlRef::expect_only_keys(std::span<const std::string_view> allowed, std::string_view what) const {
  expect_map(what);
  for (auto it = node.begin(); it != node.end(); ++it) {
    const std::string key = it->first.Scalar();
    bool known = false;
    for (std::string_view a : allowed) known = known || key == a;
    if (known) continue;
    std::string list;
    for (std::string_view a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
    YamlRef{it->first, file}.fail("unknown field '" + key + "' in " + std::string(what) + "; expected one of: " + list);
  }
}

bool YamlRef::has(std::string_view key) const { return node.IsMap() && node[std::string(key)]; }

std::optional<YamlRef> YamlRef::find(std::string_view key) const {
  if (!node.IsMap()) return std::nullopt;
  YAML::Node child = node[std::string(key)];
  if (!child) return std::nullopt;
  return YamlRef{child, file};
}

YamlRef YamlRef::at(std::string_view key, std::string_view what) const {
  expect_map(what);
  if (auto child = find(key)) return *child;
  fail("missing field '" + std::string(key) + "' in " + std::string(what));
}

YamlRef YamlRef::operator[](std::size_t index) const { return YamlRef{node[index], file}; }

ScalarValue YamlRef::scalar() const {
  ScalarValue v;
  v.scalar = node.IsScalar();
  if (v.scalar) v.text = node.Scalar();
  v.found = describe();
  v.where = where();
  return v;
}

double YamlRef::as_double(std::string_view what) const { return scalar().as_double(what); }
long long YamlRef::as_integer(std::string_view what) const { return scalar().as_integer(what); }
bool YamlRef::as_bool(std::string_view what) const { return scalar().as_bool(what); }
std::string YamlRef::as_string(std::string_view what) const { return scalar().as_string(what); }

}  // namespace avar::config
