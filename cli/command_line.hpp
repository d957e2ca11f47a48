#pragma once
// The `hofem` command line, parsed without running anything: main.cpp dispatches
// on the result, and the libFuzzer target verification/fuzz/fuzz_command_line.cpp
// drives this function alone (no solve, no file I/O).
#include "commands.hpp"

#include <cstdio>
#include <string>

namespace hofem::cli {

/// Everything the command line selects: the subcommand's name and every
/// subcommand's options (only the chosen one's are filled in).
struct CommandLine {
  std::string subcommand;  ///< the chosen subcommand's name ("quadrature", "run", ...)
  QuadratureOptions quadrature;
  BasisOptions basis;
  MeshOptions mesh;
  MmsOptions mms;
  VerifyOptions verify;
  RunOptions run;
  StudyOptions study;
  ChoicesOptions choices;
};

/// Parses argv (argv[0] the program name). Returns -1 when `out.subcommand` should
/// run; otherwise the process's exit status: 0 after --help / --help-all (printed
/// to out_stream), 2 after an error (one line, "hofem: error: ...", on err_stream).
int parse_command_line(int argc, const char* const* argv, CommandLine& out, std::FILE* out_stream,
                       std::FILE* err_stream);

}  // namespace hofem::cli
