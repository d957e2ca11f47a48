// libFuzzer target: the `hofem` command line. The input is the argument list
// separated by '\0' (command_line_input.hpp); parse_command_line only parses, so
// no command runs. Every outcome is an exit status or "run this subcommand"; an
// exception escaping (main would terminate), a crash or undefined behaviour is a
// finding.
#include "command_line.hpp"
#include "command_line_input.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string_view>

namespace {

// Help and error text goes nowhere; opened once, not per input.
std::FILE* sink() {
  static std::FILE* const null = std::fopen("/dev/null", "w");
  return null;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto words = hofem::fuzz::command_line_words({reinterpret_cast<const char*>(data), size});
  const auto argv = hofem::fuzz::argv_of(words);
  hofem::cli::CommandLine cl;
  hofem::cli::parse_command_line(static_cast<int>(words.size()), argv.data(), cl, sink(), sink());
  return 0;
}
