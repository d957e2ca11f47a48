#include "number_list.hpp"

#include "commands.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <string_view>

namespace hofem::cli {

namespace {

int parse_entry(std::string_view entry, const std::string& text, const std::string& option) {
  if (entry.empty())
    throw UsageError(fmt::format("{}: empty entry in '{}' (give whole numbers separated by commas, e.g. 1,2,3)",
                                 option, text));
  int value = 0;
  const auto [end, ec] = std::from_chars(entry.data(), entry.data() + entry.size(), value);
  if (ec == std::errc::result_out_of_range)
    throw UsageError(fmt::format("{}: '{}' is out of range", option, entry));
  if (ec != std::errc() || end != entry.data() + entry.size())
    throw UsageError(fmt::format("{}: '{}' is not a whole number (give one, or a comma list such as 1,2,3)", option,
                                 entry));
  return value;
}

}  // namespace

std::vector<int> parse_number_list(const std::string& text, const std::string& option) {
  std::vector<int> values;
  std::string_view rest = text;
  while (true) {
    const std::size_t comma = rest.find(',');
    const int v = parse_entry(rest.substr(0, comma), text, option);
    if (std::find(values.begin(), values.end(), v) != values.end())
      throw UsageError(fmt::format("{}: {} is listed twice in '{}'", option, v, text));
    values.push_back(v);
    if (comma == std::string_view::npos) return values;
    rest.remove_prefix(comma + 1);
  }
}

}  // namespace hofem::cli
