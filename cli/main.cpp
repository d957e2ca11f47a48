// hofem command-line interface: one subcommand per task, `--help` on each.
//
//   hofem quadrature --cell tet --degree 8 [--json]   the rule a query returns
//   hofem quadrature --cell tet --list                every tabulated rule of a cell
//   hofem basis --cell tet --order 3 [--json]         Lagrange nodes in Gmsh order
//   hofem mesh --box 4 --cell tet --order 2 | --msh FILE [--vtu out.vtu]
//                                                     element quality report
//   hofem mms --problem linear --order 2 --n 8 [--cell tet|hex] [--json]
//                                                     manufactured-solution errors
//                                                     (--order 1,2,3 --n 2,4,8: every
//                                                     combination, with observed rates)
//   hofem verify [--out reports/verification.json]    the verification suite
//
// Bad arguments print one line, "hofem: error: ...", and exit with status 2;
// failed verification exits with status 1. The options are parsed in
// command_line.cpp (shared with the command-line fuzz target); this file runs them.
#include "command_line.hpp"
#include "commands.hpp"
#include "scene_commands.hpp"

#include <fmt/core.h>

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

namespace {

// `hofem verify ARGS` runs `hofem-verify ARGS`, the executable beside this one
// that links the verification suite (git's way with its subcommands): the
// product binary carries no test code. Returns only if the exec fails.
int exec_verify(int argc, char** argv) {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  const std::string program = (ec ? std::filesystem::path(argv[0]) : self).parent_path() / "hofem-verify";
  std::vector<char*> args{const_cast<char*>(program.c_str())};
  int first = 1;
  while (first < argc && std::strcmp(argv[first], "verify") != 0) ++first;
  for (int i = first + 1; i < argc; ++i) args.push_back(argv[i]);
  args.push_back(nullptr);
  std::fflush(stdout);
  execv(program.c_str(), args.data());
  fmt::print(stderr, "hofem: error: verify runs '{}': {} (build the hofem-verify target)\n", program, std::strerror(errno));
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  hofem::cli::CommandLine cl;
  if (const int status = hofem::cli::parse_command_line(argc, argv, cl, stdout, stderr); status >= 0) return status;

  try {
    const std::string& sub = cl.subcommand;
    if (sub == "quadrature") return hofem::cli::run_quadrature(cl.quadrature);
    if (sub == "basis") return hofem::cli::run_basis(cl.basis);
    if (sub == "verify") return exec_verify(argc, argv);
    if (sub == "mms") return hofem::cli::run_mms(cl.mms);
    if (sub == "mesh") return hofem::cli::run_mesh(cl.mesh);
    if (sub == "run") return hofem::cli::run_scene_command(cl.run);  // --check, --print-defaults, or run_scene_file
    if (sub == "study") return hofem::cli::run_study_file(cl.study);
    if (sub == "choices") return hofem::cli::run_choices(cl.choices);
  } catch (const hofem::cli::UsageError& e) {
    fmt::print(stderr, "hofem: error: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "hofem: error: {}\n", e.what());
    return 1;
  }
  return 0;
}
