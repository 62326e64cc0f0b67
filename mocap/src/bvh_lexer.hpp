#pragma once
// Tokens of BVH text with their 1-based line and column (bytes; a tab counts one column).
// Private to the BVH reader. Tokens are runs of characters other than spaces, tabs, CR and LF;
// '{' and '}' are tokens of their own even when written against a word.

#include <charconv>
#include <cmath>
#include <cstddef>
#include <string>
#include <string_view>

#include "avar/core/input_error.hpp"

namespace avar::mocap::bvh {

struct Token {
  std::string_view text;  ///< empty at the end of the text
  int line = 1;
  int column = 1;
  bool end() const noexcept { return text.empty(); }
};

class Lexer {
 public:
  Lexer(std::string_view text, const std::string& source) : text_(text), source_(source) {}

  /// The next token, across line ends; an empty token (at the end position) when none is left.
  Token next() {
    skip_space(true);
    return take_word();
  }

  /// The next token on the current line, or an empty token at the line's end.
  Token next_on_line() {
    skip_space(false);
    if (at_line_end()) return here();
    return take_word();
  }

  /// The rest of the current line up to a '{', with surrounding spaces and tabs removed (a joint
  /// name), or an empty token when the line holds nothing more.
  Token rest_of_line() {
    skip_space(false);
    Token token = here();
    const std::size_t start = pos_;
    while (!at_line_end() && text_[pos_] != '{') ++pos_;
    std::size_t stop = pos_;
    while (stop > start && is_blank(text_[stop - 1])) --stop;
    token.text = text_.substr(start, stop - start);
    return token;
  }

  /// Skips spaces, tabs and line ends; true when the text is exhausted.
  bool at_end() {
    skip_space(true);
    return pos_ >= text_.size();
  }

  /// Moves past the current line's end; false at the end of the text.
  bool next_line() {
    while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
    if (pos_ >= text_.size()) return false;
    ++pos_;
    ++line_;
    line_start_ = pos_;
    return true;
  }

  /// Where the lexer stands (for "found end of file" and "row ends early").
  Token here() const { return Token{{}, line_, column()}; }

  [[noreturn]] void fail(const Token& at, const std::string& problem) const {
    throw InputError({source_, at.line, at.column}, problem);
  }

  /// "'text'" or "end of file" / "end of line", for "found ..." messages.
  static std::string describe(const Token& token, bool line_scope = false) {
    if (token.end()) return line_scope ? "the end of the line" : "the end of the file";
    return "'" + std::string(token.text) + "'";
  }

  /// The token as a finite number; fails naming the token otherwise ("what" says what it is).
  double number(const Token& token, const char* what) const {
    if (token.end()) fail(token, std::string("expected ") + what + " (a number), found " + describe(token, true));
    const char* first = token.text.data();
    const char* last = first + token.text.size();
    if (*first == '+' && token.text.size() > 1) ++first;  // from_chars refuses a leading plus
    double value = 0;
    const auto [ptr, ec] = std::from_chars(first, last, value);
    if (ec == std::errc::result_out_of_range)
      fail(token, std::string("expected ") + what + " to be a finite number, found " + describe(token));
    if (ec != std::errc() || ptr != last) fail(token, std::string("expected ") + what + " (a number), found " + describe(token));
    if (!std::isfinite(value)) fail(token, std::string("expected ") + what + " to be a finite number, found " + describe(token));
    return value;
  }

 private:
  static bool is_blank(char c) noexcept { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }
  bool at_line_end() const noexcept { return pos_ >= text_.size() || text_[pos_] == '\n'; }
  int column() const noexcept { return static_cast<int>(pos_ - line_start_) + 1; }

  void skip_space(bool across_lines) {
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (c == '\n') {
        if (!across_lines) return;
        ++pos_;
        ++line_;
        line_start_ = pos_;
      } else if (is_blank(c)) {
        ++pos_;
      } else {
        return;
      }
    }
  }

  Token take_word() {
    Token token = here();
    const std::size_t start = pos_;
    if (pos_ < text_.size() && (text_[pos_] == '{' || text_[pos_] == '}')) {
      ++pos_;
    } else {
      while (pos_ < text_.size() && text_[pos_] != '\n' && !is_blank(text_[pos_]) && text_[pos_] != '{' && text_[pos_] != '}')
        ++pos_;
    }
    token.text = text_.substr(start, pos_ - start);
    return token;
  }

  std::string_view text_;
  const std::string& source_;
  std::size_t pos_ = 0;
  std::size_t line_start_ = 0;
  int line_ = 1;
};

}  // namespace avar::mocap::bvh
