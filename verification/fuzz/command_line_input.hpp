#pragma once
// How a command-line fuzz input becomes argv: words separated by '\0', after
// argv[0] = "hofem". Shared by fuzz_command_line.cpp and the regression test
// (verification/unit/test_fuzz_regressions.cpp) so both replay a crasher alike.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace hofem::fuzz {

// Real command lines have a few dozen words; the cap keeps one input's parse short
// (CLI11's work grows faster than the argument count) without hiding a parsing path.
inline constexpr std::size_t kMaxArguments = 128;

/// "hofem" then the input's '\0'-separated words (a trailing '\0' gives a last,
/// empty word), at most kMaxArguments in all.
inline std::vector<std::string> command_line_words(std::string_view input) {
  std::vector<std::string> words{"hofem"};
  if (input.empty()) return words;
  std::size_t begin = 0;
  while (words.size() < kMaxArguments) {
    const std::size_t end = input.find('\0', begin);
    words.emplace_back(input.substr(begin, end == std::string_view::npos ? std::string_view::npos : end - begin));
    if (end == std::string_view::npos) break;
    begin = end + 1;
  }
  return words;
}

/// argv for `words`, null-terminated as the C runtime hands it to main.
inline std::vector<const char*> argv_of(const std::vector<std::string>& words) {
  std::vector<const char*> argv;
  for (const auto& w : words) argv.push_back(w.c_str());
  argv.push_back(nullptr);
  return argv;
}

}  // namespace hofem::fuzz
