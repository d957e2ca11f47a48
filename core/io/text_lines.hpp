#pragma once
// Line-by-line reading of text input with line numbers, for readers whose every
// error must name "<file>:<line>" (the Gmsh reader; later the scene files).
// Blank lines are skipped; a line is split into whitespace-separated tokens, and
// typed accessors check each token, failing with MeshError naming the line.
#include "mesh/mesh.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <climits>
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

namespace hofem::detail {

// A token for a message, shortened: garbage input may hold huge or binary "tokens".
inline std::string quoted(std::string_view s) {
  return s.size() <= 40 ? fmt::format("'{}'", s) : fmt::format("'{}...'", s.substr(0, 40));
}

inline bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// Cursor over the non-blank lines of the text: line number and whitespace-separated tokens.
class TextLines {
 public:
  TextLines(std::string_view text, std::string_view origin) : text_(text), origin_(origin) {}

  bool next() {
    while (pos_ < text_.size()) {
      std::size_t end = text_.find('\n', pos_);
      if (end == std::string_view::npos) end = text_.size();
      const std::string_view line = text_.substr(pos_, end - pos_);
      pos_ = end + 1;
      ++number_;
      tokens_.clear();
      for (std::size_t i = 0; i < line.size();) {
        while (i < line.size() && is_blank(line[i])) ++i;
        std::size_t j = i;
        while (j < line.size() && !is_blank(line[j])) ++j;
        if (j > i) tokens_.push_back(line.substr(i, j - i));
        i = j;
      }
      if (!tokens_.empty()) return true;
    }
    return false;
  }
  int number() const { return number_; }
  std::size_t size() const { return tokens_.size(); }
  std::string_view tok(std::size_t i) const { return tokens_[i]; }
  /// The line from token i to its last token.
  std::string_view rest(std::size_t i) const {
    const char* end = tokens_.back().data() + tokens_.back().size();
    return {tokens_[i].data(), static_cast<std::size_t>(end - tokens_[i].data())};
  }

  [[noreturn]] void fail_at(int line, const std::string& what) const {
    throw MeshError(fmt::format("{}:{}: {}", origin_, std::max(line, 1), what));
  }
  [[noreturn]] void fail(const std::string& what) const { fail_at(number_, what); }

  long long integer(std::size_t i, std::string_view what, long long lo, long long hi) const {
    const std::string_view s = tokens_[i];
    long long v = 0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    const bool whole = end == s.data() + s.size();
    if (ec == std::errc::result_out_of_range || (ec == std::errc() && whole && (v < lo || v > hi)))
      fail(fmt::format("{} {} is out of range [{}, {}]", what, quoted(s), lo, hi));
    if (ec != std::errc() || !whole) fail(fmt::format("expected an integer ({}), got {}", what, quoted(s)));
    return v;
  }
  int small(std::size_t i, std::string_view what, int lo = INT_MIN, int hi = INT_MAX) const {
    return static_cast<int>(integer(i, what, lo, hi));
  }
  double real(std::size_t i, std::string_view what) const {
    std::string_view s = tokens_[i];
    if (s.size() > 1 && s[0] == '+') s.remove_prefix(1);  // from_chars rejects a leading '+'
    double v = 0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec == std::errc::result_out_of_range) fail(fmt::format("{} {} is out of range", what, quoted(tokens_[i])));
    if (ec != std::errc() || end != s.data() + s.size())
      fail(fmt::format("expected a number ({}), got {}", what, quoted(tokens_[i])));
    if (!std::isfinite(v)) fail(fmt::format("{} {} is not finite", what, quoted(tokens_[i])));
    return v;
  }
  void expect_size(std::size_t n, std::string_view what) const {
    if (tokens_.size() != n)
      fail(fmt::format("expected {} value{} ({}), got {}", n, n == 1 ? "" : "s", what, tokens_.size()));
  }

 private:
  std::string_view text_, origin_;
  std::size_t pos_ = 0;
  int number_ = 0;
  std::vector<std::string_view> tokens_;
};

}  // namespace hofem::detail
