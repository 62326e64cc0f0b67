// Bad input end to end: seeded mutations of every bundled example rig and show (byte flips,
// truncations, deleted and duplicated lines, numbers replaced by nan, inf or huge values, duplicate
// keys, YAML alias bombs, unknown fields, numbers with units, values of the wrong type) through
// the real `avar` binary, `avar check` and `avar play --fast --sim`, each in its own process with a
// time limit. Every run must exit 0 or 2, and a refusal (2) must name file:line:col; never a crash,
// a hang, a sanitizer report or another exit code. The seed is printed with every failure;
// AVAR_SWEEP_SEED=<n> replays another family.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "../support/child_process.hpp"
#include "../support/temp_file.hpp"
#include "avar/exit_codes.hpp"

namespace avar::app {
namespace {

struct SweepPair {
  const char* show;
  const char* rig;
};

// Every bundled show with the rig it is written for, and every bundled rig at least once.
constexpr SweepPair kSweepPairs[] = {
    {"hello-head", "hello-head"},     {"curves-tour", "hello-head"}, {"layered-head", "hello-head"},
    {"hello-head", "maestro-usb"},    {"arm-wave", "dynamixel-arm"}, {"arm-wave", "feetech-arm"},
    {"figure-eight", "gaze-head"},    {"look-around", "gaze-head"},  {"haunt-prop", "haunt-prop"},
    {"mixed-figure", "mixed-figure"}, {"odrive-arm", "odrive-arm"},  {"turntable-tour", "cia402-turntable"},
    {"lively-head", "hello-head"},
};

enum class SweepMutation {
  flip_byte,
  truncate,
  delete_line,
  duplicate_line,
  bad_number,
  duplicate_key,
  alias_bomb,
  self_alias,
  unknown_field,
  wrong_unit,
  wrong_type,
  count
};

const char* sweep_mutation_name(SweepMutation m) {
  constexpr const char* kNames[] = {"flip_byte",  "truncate",   "delete_line",   "duplicate_line", "bad_number", "duplicate_key",
                                    "alias_bomb", "self_alias", "unknown_field", "wrong_unit",     "wrong_type"};
  return kNames[static_cast<int>(m)];
}

std::string sweep_read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> sweep_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::stringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::string sweep_join(const std::vector<std::string>& lines) {
  std::string text;
  for (const auto& line : lines) text += line + "\n";
  return text;
}

/// Positions and lengths of the regex's matches in text (the first group's, when it has one).
std::vector<std::pair<std::size_t, std::size_t>> sweep_matches(const std::string& text, const std::regex& re) {
  std::vector<std::pair<std::size_t, std::size_t>> found;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), re); it != std::sregex_iterator(); ++it) {
    const int group = it->size() > 1 ? 1 : 0;
    found.emplace_back(static_cast<std::size_t>(it->position(group)), static_cast<std::size_t>(it->length(group)));
  }
  return found;
}

template <typename T>
const T& sweep_pick(const std::vector<T>& items, std::mt19937_64& rng) {
  return items[std::uniform_int_distribution<std::size_t>(0, items.size() - 1)(rng)];
}

// Scalar values after "key: " (block or flow), and numbers; both outside comments is not needed:
// a mutation inside a comment simply leaves the file valid.
const std::regex kSweepValue(R"(\w: ([^\s,{}\[\]#][^,{}\[\]#\n]*))");
const std::regex kSweepNumber(R"((?:^|[\s\[{,:])(-?[0-9]+(?:\.[0-9]+)?(?:[eE][-+]?[0-9]+)?))");
const std::regex kSweepKey(R"((\w+): )");

/// A billion laughs: nine levels of nine aliases each, as one flow value.
std::string sweep_alias_bomb() {
  std::string bomb = "[&l0 [1, 1, 1, 1, 1, 1, 1, 1, 1]";
  for (int level = 1; level < 9; ++level) {
    bomb += ", &l" + std::to_string(level) + " [";
    for (int i = 0; i < 9; ++i) bomb += (i ? ", *l" : "*l") + std::to_string(level - 1);
    bomb += "]";
  }
  return bomb + "]";
}

std::string sweep_replace(std::string text, std::pair<std::size_t, std::size_t> at, const std::string& with) {
  return text.replace(at.first, at.second, with);
}

/// The text with one mutation of kind m; unchanged when the file offers no place for it.
std::string sweep_mutate(const std::string& text, SweepMutation m, std::mt19937_64& rng) {
  const auto below = [&](std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng); };
  std::vector<std::string> lines = sweep_lines(text);
  const auto values = sweep_matches(text, kSweepValue);
  const auto numbers = sweep_matches(text, kSweepNumber);
  switch (m) {
    case SweepMutation::flip_byte: {
      std::string out = text;
      out[below(out.size())] = static_cast<char>(below(256));
      return out;
    }
    case SweepMutation::truncate: return text.substr(0, below(text.size()));
    case SweepMutation::delete_line:
      lines.erase(lines.begin() + static_cast<std::ptrdiff_t>(below(lines.size())));
      return sweep_join(lines);
    case SweepMutation::duplicate_line: {
      const std::size_t i = below(lines.size());
      lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(i), lines[i]);
      return sweep_join(lines);
    }
    case SweepMutation::bad_number: {
      if (numbers.empty()) return text;
      static const std::vector<std::string> kBad{
          ".nan", "nan", ".inf", "-.inf", "1e308", "-1e308", "1e999", "99999999999999999999", "-0", "0"};
      return sweep_replace(text, sweep_pick(numbers, rng), sweep_pick(kBad, rng));
    }
    case SweepMutation::duplicate_key: {
      // The same key again in its map: in a flow map after the pair, in a block map as a second line.
      const auto keys = sweep_matches(text, kSweepKey);
      if (keys.empty()) return text;
      const auto key = sweep_pick(keys, rng);
      const std::size_t line_start = text.rfind('\n', key.first) == std::string::npos ? 0 : text.rfind('\n', key.first) + 1;
      const std::size_t line_end = std::min(text.find('\n', key.first), text.size());
      const std::string line = text.substr(line_start, line_end - line_start);
      const std::string name = text.substr(key.first, key.second);
      if (line.find('{') != std::string::npos && line.find('{') < key.first - line_start)
        return std::string(text).insert(key.first, name + ": 0, ");
      return std::string(text).insert(line_end, "\n" + line);
    }
    case SweepMutation::alias_bomb:
      return values.empty() ? text : sweep_replace(text, sweep_pick(values, rng), sweep_alias_bomb());
    case SweepMutation::self_alias:
      return values.empty() ? text : sweep_replace(text, sweep_pick(values, rng), "&self [*self, *self]");
    case SweepMutation::unknown_field: {
      const auto keys = sweep_matches(text, kSweepKey);
      if (keys.empty()) return text;
      const auto key = sweep_pick(keys, rng);
      return std::string(text).insert(
          key.first, "sweep_unknown_field: 1\n" + std::string(key.first - (text.rfind('\n', key.first) + 1), ' '));
    }
    case SweepMutation::wrong_unit: {
      if (numbers.empty()) return text;
      static const std::vector<std::string> kUnits{" s", "ms", " deg", " %", "Hz", " rad/s", " mm"};
      const auto at = sweep_pick(numbers, rng);
      return std::string(text).insert(at.first + at.second, sweep_pick(kUnits, rng));
    }
    case SweepMutation::wrong_type: {
      if (values.empty()) return text;
      static const std::vector<std::string> kWrong{"{x: 1}", "[1, 2]", "text", "\"\"", "~", "true", "[]", "{}"};
      return sweep_replace(text, sweep_pick(values, rng), sweep_pick(kWrong, rng));
    }
    case SweepMutation::count: break;
  }
  return text;
}

struct SweepRun {
  int code;
  std::string err;
};

SweepRun sweep_avar(std::vector<std::string> args) {
  args.insert(args.begin(), AVAR_BINARY);
  testing::ChildProcess child(args);
  if (!child.started()) return {-3, "could not start " AVAR_BINARY};
  const int code = child.wait_for(std::chrono::seconds(60));
  return {code, child.err()};
}

/// Empty when the run is acceptable; else what is wrong with it.
std::string sweep_verdict(const SweepRun& run, const std::string& show, const std::string& rig) {
  if (run.code == testing::ChildProcess::kTimedOut) return "did not finish within 60 s (a hang)";
  if (run.code == kExitOk) return "";
  if (run.code != kExitBadInput) return "exit code " + std::to_string(run.code) + " (expected 0 or 2)";
  const std::regex located("(" + std::regex_replace(show + "|" + rig, std::regex(R"([.^$()\[\]{}*+?\\])"), R"(\$&)") +
                           "):[0-9]+:[0-9]+: ");
  if (!std::regex_search(run.err, located)) return "refused without naming file:line:col";
  return "";
}

TEST(BadInputSweep, MutatedExamplesAreAcceptedOrRefusedWithALocationNeverCrash) {
  const char* seed_text = std::getenv("AVAR_SWEEP_SEED");
  const std::uint64_t seed = seed_text ? std::strtoull(seed_text, nullptr, 10) : 20261203;
  // One per mutation kind and pair: under the sanitizers each case is two runs of the avar binary.
  constexpr int kCases = 143;
  // A mutated file that still reads plays its whole show: only so many of those, the rest checked.
  constexpr int kMaxPlayedWhole = 4;
  int played_whole = 0, refused = 0;
  const std::string dir = testing::temp_path("sweep");
  std::string mkdir = "mkdir -p " + dir;
  ASSERT_EQ(std::system(mkdir.c_str()), 0);
  for (int i = 0; i < kCases; ++i) {
    std::mt19937_64 rng(seed + static_cast<std::uint64_t>(i));
    const SweepPair& pair = kSweepPairs[static_cast<std::size_t>(i) % std::size(kSweepPairs)];
    const auto mutation =
        static_cast<SweepMutation>((i / static_cast<int>(std::size(kSweepPairs))) % static_cast<int>(SweepMutation::count));
    const bool mutate_rig =
        (i / static_cast<int>(std::size(kSweepPairs) * static_cast<std::size_t>(SweepMutation::count))) % 2 == 1;
    std::string show = AVAR_SOURCE_DIR "/examples/shows/" + std::string(pair.show) + ".yaml";
    std::string rig = AVAR_SOURCE_DIR "/examples/rigs/" + std::string(pair.rig) + ".yaml";
    std::string& target = mutate_rig ? rig : show;
    const std::string mutated = sweep_mutate(sweep_read(target), mutation, rng);
    target = dir + "/case" + std::to_string(i) + "-" + (mutate_rig ? pair.rig : pair.show) + ".yaml";
    std::ofstream(target, std::ios::binary) << mutated;
    const std::string what = "seed " + std::to_string(seed) + " case " + std::to_string(i) + ": " +
                             sweep_mutation_name(mutation) + " of the " + (mutate_rig ? "rig " : "show ") + target + " (show " +
                             show + ", rig " + rig + ")";

    const SweepRun checked = sweep_avar({"check", show, "--rig", rig});
    const std::string check_problem = sweep_verdict(checked, show, rig);
    EXPECT_EQ(check_problem, "") << "avar check, " << what << "\n" << checked.err.substr(0, 2000);
    if (checked.code == kExitBadInput) ++refused;
    if (checked.code == kExitOk && played_whole >= kMaxPlayedWhole) continue;
    if (checked.code == kExitOk) ++played_whole;
    const SweepRun played = sweep_avar({"play", show, "--rig", rig, "--fast", "--sim", "--no-progress"});
    EXPECT_EQ(sweep_verdict(played, show, rig), "") << "avar play --fast --sim, " << what << "\n" << played.err.substr(0, 2000);
    // What check refuses, play refuses too, before anything moves.
    if (checked.code == kExitBadInput) {
      EXPECT_EQ(played.code, kExitBadInput) << what << "\n" << played.err.substr(0, 2000);
    }
  }
  // The sweep exercises refusals: most mutations break a file.
  EXPECT_GT(refused, kCases / 2);
}

}  // namespace
}  // namespace avar::app
