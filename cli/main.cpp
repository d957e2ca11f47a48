// hofem command-line interface: one subcommand per task, `--help` on each.
//
//   hofem quadrature --cell tet --degree 8 [--json]   the rule a query returns
//   hofem quadrature --cell tet --list                every tabulated rule of a cell
//   hofem basis --cell tet --order 3 [--json]         Lagrange nodes in Gmsh order
//   hofem mesh --box 4 --cell tet --order 2 | --msh FILE [--vtu out.vtu]
//                                                     element quality report
//   hofem mms --problem linear --order 2 --n 8 [--cell tet|hex] [--json]
//                                                     manufactured-solution errors
//   hofem verify [--out reports/verification.json]    the verification suite
//
// Bad arguments print one line, "hofem: error: ...", and exit with status 2;
// failed verification exits with status 1. The options are parsed in
// command_line.cpp (shared with the command-line fuzz target); this file runs them.
#include "command_line.hpp"
#include "commands.hpp"

#include <fmt/core.h>

#include <cstdio>
#include <exception>
#include <string>

int main(int argc, char** argv) {
  hofem::cli::CommandLine cl;
  if (const int status = hofem::cli::parse_command_line(argc, argv, cl, stdout, stderr); status >= 0) return status;

  try {
    const std::string& sub = cl.subcommand;
    if (sub == "quadrature") return hofem::cli::run_quadrature(cl.quadrature);
    if (sub == "basis") return hofem::cli::run_basis(cl.basis);
    if (sub == "verify") return hofem::cli::run_verify(cl.verify);
    if (sub == "mms") return hofem::cli::run_mms(cl.mms);
    if (sub == "mesh") return hofem::cli::run_mesh(cl.mesh);
    if (sub == "run") return hofem::cli::run_scene_file(cl.run);
    if (sub == "study") return hofem::cli::run_study_file(cl.study);
  } catch (const hofem::cli::UsageError& e) {
    fmt::print(stderr, "hofem: error: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "hofem: error: {}\n", e.what());
    return 1;
  }
  return 0;
}
