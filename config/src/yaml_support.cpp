#include "yaml_support.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <unordered_map>
#include <vector>

namespace avar::config {
namespace {

/// Refuses what yaml-cpp accepts but a rig or show must not hold: a key twice in one map (the
/// second silently won), and a document that aliases expand past kMaxValues values (a billion
/// laughs, or an anchor that contains itself). Walks without recursion, so a cycle cannot
/// exhaust the stack: the budget ends it.
void check_document(const YAML::Node& root, const std::string& path) {
  constexpr std::size_t kMaxValues = 1'000'000;
  const auto at = [&](const YAML::Node& n) {
    const YAML::Mark m = n.Mark();
    return m.is_null() ? SourceLocation{path, 0, 0} : SourceLocation{path, m.line + 1, m.column + 1};
  };
  std::vector<YAML::Node> pending{root};
  std::size_t visited = 0;
  while (!pending.empty()) {
    const YAML::Node node = pending.back();
    pending.pop_back();
    if (++visited > kMaxValues)
      throw InputError(at(node), "the document expands to more than " + std::to_string(kMaxValues) +
                                     " values (aliases repeating an anchor); expected a rig or show without such nesting");
    if (node.IsSequence()) {
      for (const YAML::Node& item : node) pending.push_back(item);
    } else if (node.IsMap()) {
      std::unordered_map<std::string, YAML::Mark> seen;
      for (const auto& entry : node) {
        if (entry.first.IsScalar()) {
          const auto [first, inserted] = seen.emplace(entry.first.Scalar(), entry.first.Mark());
          if (!inserted)
            throw InputError(at(entry.first), "duplicate key '" + entry.first.Scalar() + "' (first at line " +
                                                  std::to_string(first->second.line + 1) + ", column " +
                                                  std::to_string(first->second.column + 1) +
                                                  "); expected each key once in a map");
        }
        pending.push_back(entry.first);
        pending.push_back(entry.second);
      }
    }
  }
}

}  // namespace

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
    check_document(root, path);
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
