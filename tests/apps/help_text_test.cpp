// The help of every command, as a user (and the docs' generated command reference) reads it:
// every example file it names exists, and the commands that set things up teach by example.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "../support/cli_run.hpp"

namespace avar::app {
namespace {

std::string help_of(const std::vector<std::string>& path) {
  std::vector<std::string> args = path;
  args.emplace_back("--help");
  const testing::CliResult r = testing::run_avar(args);
  EXPECT_EQ(r.code, 0) << "avar " << ::testing::PrintToString(path) << " --help: " << r.err;
  return r.out;
}

// The names listed under the help's "Subcommands:" heading, in order; of an entry with aliases
// ("can, slcan") the first name.
std::vector<std::string> subcommands_in(const std::string& help) {
  std::vector<std::string> names;
  std::istringstream in(help);
  std::string line;
  bool listing = false;
  while (std::getline(in, line)) {
    if (line == "Subcommands:" || line == "SUBCOMMANDS:") {
      listing = true;
    } else if (listing) {
      static const std::regex entry(R"(^  ([^\s,]+).*$)");
      std::smatch m;
      if (!std::regex_match(line, m, entry)) break;
      names.push_back(m[1]);
    }
  }
  return names;
}

std::string joined(const std::vector<std::string>& path) {
  std::string s = "avar";
  for (const auto& p : path) s += " " + p;
  return s;
}

// Every command path from the top, depth first: {}, {"play"}, ..., {"sim", "maestro"}, ...
// A listed name whose help is not its own (CLI11 answers an unknown name with the parent's help)
// fails here instead of being walked again.
void collect(const std::vector<std::string>& path, std::vector<std::vector<std::string>>& all) {
  all.push_back(path);
  const std::string help = help_of(path);
  if (help.find("Usage: " + joined(path)) == std::string::npos) {
    ADD_FAILURE() << joined(path) << " --help is not that command's help:\n" << help;
    return;
  }
  for (const std::string& name : subcommands_in(help)) {
    std::vector<std::string> sub = path;
    sub.push_back(name);
    collect(sub, all);
  }
}

TEST(HelpText, EveryCommandAndSubcommandHasHelpAndNamesOnlyExampleFilesThatExist) {
  std::vector<std::vector<std::string>> all;
  collect({}, all);
  ASSERT_GT(all.size(), 12u);  // the top level, its commands and the nested ones
  bool nested = false;
  static const std::regex example_path(R"(examples/[A-Za-z0-9_./-]*[A-Za-z0-9])");
  for (const auto& path : all) {
    nested = nested || path.size() > 1;
    const std::string help = help_of(path);
    EXPECT_FALSE(help.empty()) << joined(path);
    for (std::sregex_iterator it(help.begin(), help.end(), example_path), end; it != end; ++it) {
      const std::string file = it->str();
      EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(AVAR_SOURCE_DIR) / file))
          << joined(path) << " --help names " << file << ", which does not exist";
    }
  }
  EXPECT_TRUE(nested) << "no nested subcommand found (avar sim maestro, avar inputs monitor...)";
}

TEST(HelpText, SetUpCommandsTeachWhatTheyDoWithAnExampleAndWhatTheOutputMeans) {
  const std::string check = help_of({"check"});
  EXPECT_NE(check.find("Example"), std::string::npos) << check;
  EXPECT_NE(check.find("avar check examples/shows/"), std::string::npos) << check;
  EXPECT_NE(check.find("infeasible:"), std::string::npos) << "check's help explains its output: " << check;

  const std::string inputs = help_of({"inputs"});
  EXPECT_NE(inputs.find("Example"), std::string::npos) << inputs;
  EXPECT_NE(inputs.find("avar inputs monitor --input"), std::string::npos) << inputs;
  EXPECT_NE(inputs.find("avar inputs learn --rig"), std::string::npos) << inputs;

  const std::string monitor = help_of({"inputs", "monitor"});
  EXPECT_NE(monitor.find("Example"), std::string::npos) << monitor;
  EXPECT_NE(monitor.find("avar inputs monitor --input"), std::string::npos) << monitor;
  EXPECT_NE(monitor.find("bipolar"), std::string::npos) << "monitor's help explains its lines: " << monitor;

  const std::string puppet = help_of({"puppet"});
  EXPECT_EQ(puppet.find("puppet-head"), std::string::npos) << puppet;
}

}  // namespace
}  // namespace avar::app
