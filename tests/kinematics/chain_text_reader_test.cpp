#include "avar/kinematics/chain_text_reader.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include "../support/temp_file.hpp"
#include "test_models.hpp"

namespace avar::kinematics {
namespace {

std::vector<DhChain> read_text(const std::string& text) {
  std::istringstream in(text);
  return read_dh_chains(in, "arm.txt");
}

/// The message of the InputError that reading `text` throws; empty when nothing is thrown.
std::string error_of(const std::string& text) {
  try {
    read_text(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ChainTextReader, ReadsChainsRowsAndTheirLines) {
  const auto chains = read_text(
      "# two arms\n"
      "\n"
      "chain pan_tilt 2   # a comment after the header\n"
      "\t0.1  1.5  +0.2  -0.3  -1  1\n"
      "  # a comment between rows\n"
      "0 0 0.05 0 -2.5 2.5# touching comment\n"
      "chain slider 1\n"
      "1e-1 -1.5707963267948966 0 0 -3.14 3.14\n");
  ASSERT_EQ(chains.size(), 2u);
  EXPECT_EQ(chains[0].name, "pan_tilt");
  EXPECT_EQ(chains[0].where.line, 3);
  ASSERT_EQ(chains[0].rows.size(), 2u);
  const DhRow& r = chains[0].rows[0];
  EXPECT_EQ(r.a, 0.1);
  EXPECT_EQ(r.alpha, 1.5);
  EXPECT_EQ(r.d, 0.2);
  EXPECT_EQ(r.theta, -0.3);
  EXPECT_EQ(r.lower, -1);
  EXPECT_EQ(r.upper, 1);
  EXPECT_EQ(r.where.file, "arm.txt");
  EXPECT_EQ(r.where.line, 4);
  EXPECT_EQ(r.where.column, 2);
  EXPECT_EQ(chains[0].rows[1].where.line, 6);
  EXPECT_EQ(chains[0].rows[1].upper, 2.5);
  EXPECT_EQ(chains[1].name, "slider");
  EXPECT_EQ(chains[1].rows[0].alpha, -std::numbers::pi / 2);
}

TEST(ChainTextReader, ReadsAFileByPath) {
  const std::string path = testing::write_temp_file("arm.txt", "chain arm 1\n0.5 0 0 0 -1 1\n");
  const auto chains = read_dh_chains(path);
  ASSERT_EQ(chains.size(), 1u);
  EXPECT_EQ(chains[0].rows[0].a, 0.5);
  EXPECT_EQ(chains[0].rows[0].where.file, path);
}

TEST(ChainTextReader, NamesAMissingFile) {
  const std::string path = testing::temp_path("absent.txt");
  try {
    read_dh_chains(path);
    FAIL() << "a missing file was read";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), path + ": cannot open the file; expected a readable DH chain file");
  }
}

TEST(ChainTextReader, RejectsMalformedHeaders) {
  EXPECT_EQ(error_of("chain arm\n"), "arm.txt:1:1: expected 'chain <name> <dof>'");
  EXPECT_EQ(error_of("  chain arm 2 extra\n"), "arm.txt:1:15: unexpected 'extra' after 'chain <name> <dof>'");
  EXPECT_EQ(error_of("chain arm two\n"), "arm.txt:1:11: expected the number of joints (a positive integer), found 'two'");
  EXPECT_EQ(error_of("chain arm 0\n"), "arm.txt:1:11: expected the number of joints (a positive integer), found '0'");
  EXPECT_EQ(error_of("chain arm 2.5\n"), "arm.txt:1:11: expected the number of joints (a positive integer), found '2.5'");
  EXPECT_EQ(error_of("chain arm 1\n0 0 0 0 -1 1\n\nchain arm 1\n"),
            "arm.txt:4:7: chain 'arm' is already defined at line 1; expected unique chain names");
}

TEST(ChainTextReader, RejectsRowsOutsideTheirChain) {
  EXPECT_EQ(error_of("# no header\n0 0 0 0 -1 1\n"),
            "arm.txt:2:1: found a joint row before any chain; expected 'chain <name> <dof>' first");
  EXPECT_EQ(error_of("chain arm 1\n0 0 0 0 -1 1\n 1 0 0 0 -1 1\n"),
            "arm.txt:3:2: found more joint rows than the 1 that chain 'arm' declares; expected 'chain <name> <dof>' or "
            "the end of the file");
}

TEST(ChainTextReader, RejectsChainsWithTooFewRows) {
  EXPECT_EQ(error_of("chain arm 3\n0 0 0 0 -1 1\n0 0 0 0 -1 1\nchain leg 1\n0 0 0 0 -1 1\n"),
            "arm.txt:4:1: found a new chain after 2 of the 3 joint rows that chain 'arm' declares at line 1; expected its "
            "remaining rows first");
  EXPECT_EQ(error_of("\nchain arm 3\n0 0 0 0 -1 1\n"), "arm.txt:2:1: the file ends after 1 of the 3 joint rows that chain 'arm' declares; expected all of them");
}

TEST(ChainTextReader, RejectsRowsThatAreNotSixNumbers) {
  EXPECT_EQ(error_of("chain arm 1\n0 0 0 0 -1\n"), "arm.txt:2:1: expected six numbers (a alpha d theta lower upper), found 5");
  EXPECT_EQ(error_of("chain arm 1\n0 0 0 0 -1 1 7\n"),
            "arm.txt:2:14: unexpected '7' after the six numbers a alpha d theta lower upper");
  EXPECT_EQ(error_of("chain arm 1\n0 0 zero 0 -1 1\n"), "arm.txt:2:5: expected a number for d, found 'zero'");
  EXPECT_EQ(error_of("chain arm 1\n0 0 0 0 -1 1,\n"), "arm.txt:2:12: expected a number for upper, found '1,'");
  EXPECT_EQ(error_of("chain arm 1\n0 +-1 0 0 -1 1\n"), "arm.txt:2:3: expected a number for alpha, found '+-1'");
}

TEST(ChainTextReader, RejectsAFileWithoutChains) {
  EXPECT_EQ(error_of("# nothing here\n\n"), "arm.txt: found no chains; expected at least one 'chain <name> <dof>' line");
}

using ChainTextReaderOnBenchChains = test::BenchChains;

TEST_F(ChainTextReaderOnBenchChains, ReadsTheSharedReferenceChains) {
  ASSERT_EQ(chains.size(), 2u);
  EXPECT_EQ(chains[0].name, "ur5");
  EXPECT_EQ(chains[1].name, "iiwa7");
  ASSERT_EQ(chains[0].rows.size(), 6u);
  ASSERT_EQ(chains[1].rows.size(), 7u);
  EXPECT_EQ(chains[0].rows[0].d, 0.089159);
  EXPECT_EQ(chains[0].rows[2].a, -0.39225);
  EXPECT_EQ(chains[0].rows[2].upper, std::numbers::pi);
  EXPECT_EQ(chains[1].rows[6].d, 0.126);
  // Every row's line holds its numbers.
  std::ifstream in(test::kBenchChainsPath);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  for (const DhChain& chain : chains) {
    EXPECT_EQ(lines.at(static_cast<std::size_t>(chain.where.line - 1)).rfind("chain " + chain.name, 0), 0u);
    for (const DhRow& row : chain.rows) {
      std::istringstream numbers(lines.at(static_cast<std::size_t>(row.where.line - 1)));
      double a = 0;
      numbers >> a;
      EXPECT_EQ(a, row.a) << "line " << row.where.line;
    }
  }
}

}  // namespace
}  // namespace avar::kinematics
