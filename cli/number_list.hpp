#pragma once
// Comma lists of whole numbers on the command line ("--order 1,2,3"): the
// options that may run several cases at once take one, a single number being
// a list of one.
#include <string>
#include <vector>

namespace hofem::cli {

/// The numbers of `text` ("2,4,8"; each optionally signed, in the range of int),
/// in the order given. Throws UsageError naming `option` for an empty entry
/// ("1,,2"), an entry that is not a whole number ("a", "1.5"), one out of the
/// range of int, and a number listed twice (the cases would repeat). The range
/// each option allows is checked by its command.
std::vector<int> parse_number_list(const std::string& text, const std::string& option);

}  // namespace hofem::cli
