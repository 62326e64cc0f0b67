#include "avar/kinematics/chain_text_reader.hpp"

#include <array>
#include <charconv>
#include <fstream>
#include <string_view>

namespace avar::kinematics {
namespace {

struct Word {
  std::string_view text;
  int column = 0;  ///< 1-based
};

/// The whitespace-separated words of a line, up to a '#'.
std::vector<Word> words_of(std::string_view line) {
  std::vector<Word> words;
  std::size_t i = 0;
  while (i < line.size() && line[i] != '#') {
    if (line[i] == ' ' || line[i] == '\t' || line[i] == '\r') {
      ++i;
      continue;
    }
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r' && line[i] != '#') ++i;
    words.push_back({line.substr(start, i - start), static_cast<int>(start) + 1});
  }
  return words;
}

template <typename Number>
bool parse_whole(std::string_view text, Number& value) {
  if (text.size() > 1 && text.front() == '+' && text[1] != '-') text.remove_prefix(1);
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc() && end == text.data() + text.size();
}

std::string quoted(std::string_view text) { return "'" + std::string(text) + "'"; }

class Reader {
 public:
  explicit Reader(const std::string& file) : file_(file) {}

  void line(std::string_view text) {
    ++line_number_;
    const std::vector<Word> words = words_of(text);
    if (words.empty()) return;
    if (words[0].text == "chain")
      header(words);
    else
      row(words);
  }

  std::vector<DhChain> finish() {
    if (chains_.empty()) throw InputError({file_, 0, 0}, "found no chains; expected at least one 'chain <name> <dof>' line");
    if (missing_rows() > 0)
      throw InputError(chains_.back().where, "the file ends after " + std::to_string(chains_.back().rows.size()) + " of the " +
                                                 std::to_string(declared_dof_) + " joint rows that chain '" +
                                                 chains_.back().name + "' declares; expected all of them");
    return std::move(chains_);
  }

 private:
  SourceLocation at(const Word& word) const { return {file_, line_number_, word.column}; }
  std::size_t missing_rows() const { return chains_.empty() ? 0 : declared_dof_ - chains_.back().rows.size(); }

  void header(const std::vector<Word>& words) {
    if (missing_rows() > 0)
      throw InputError(at(words[0]), "found a new chain after " + std::to_string(chains_.back().rows.size()) + " of the " +
                                         std::to_string(declared_dof_) + " joint rows that chain '" + chains_.back().name +
                                         "' declares at line " + std::to_string(chains_.back().where.line) +
                                         "; expected its remaining rows first");
    if (words.size() < 3) throw InputError(at(words[0]), "expected 'chain <name> <dof>'");
    if (words.size() > 3) throw InputError(at(words[3]), "unexpected " + quoted(words[3].text) + " after 'chain <name> <dof>'");
    for (const DhChain& chain : chains_)
      if (chain.name == words[1].text)
        throw InputError(at(words[1]), "chain " + quoted(words[1].text) + " is already defined at line " +
                                           std::to_string(chain.where.line) + "; expected unique chain names");
    long long dof = 0;
    if (!parse_whole(words[2].text, dof) || dof <= 0)
      throw InputError(at(words[2]), "expected the number of joints (a positive integer), found " + quoted(words[2].text));
    chains_.push_back({std::string(words[1].text), {}, at(words[0])});
    declared_dof_ = static_cast<std::size_t>(dof);
  }

  void row(const std::vector<Word>& words) {
    if (chains_.empty())
      throw InputError(at(words[0]), "found a joint row before any chain; expected 'chain <name> <dof>' first");
    if (missing_rows() == 0)
      throw InputError(at(words[0]), "found more joint rows than the " + std::to_string(declared_dof_) + " that chain '" +
                                         chains_.back().name + "' declares; expected 'chain <name> <dof>' or the end of the file");
    static constexpr std::array<const char*, 6> kFields{"a", "alpha", "d", "theta", "lower", "upper"};
    if (words.size() > kFields.size())
      throw InputError(at(words[kFields.size()]), "unexpected " + quoted(words[kFields.size()].text) +
                                                      " after the six numbers a alpha d theta lower upper");
    if (words.size() < kFields.size())
      throw InputError(at(words[0]), "expected six numbers (a alpha d theta lower upper), found " + std::to_string(words.size()));
    std::array<double, 6> values{};
    for (std::size_t i = 0; i < kFields.size(); ++i)
      if (!parse_whole(words[i].text, values[i]))
        throw InputError(at(words[i]), std::string("expected a number for ") + kFields[i] + ", found " + quoted(words[i].text));
    chains_.back().rows.push_back({values[0], values[1], values[2], values[3], values[4], values[5], at(words[0])});
  }

  std::string file_;
  int line_number_ = 0;
  std::vector<DhChain> chains_;
  std::size_t declared_dof_ = 0;  ///< of the last chain
};

}  // namespace

std::vector<DhChain> read_dh_chains(std::istream& in, const std::string& file) {
  Reader reader(file);
  for (std::string text; std::getline(in, text);) reader.line(text);
  return reader.finish();
}

std::vector<DhChain> read_dh_chains(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError({path, 0, 0}, "cannot open the file; expected a readable DH chain file");
  return read_dh_chains(in, path);
}

}  // namespace avar::kinematics
