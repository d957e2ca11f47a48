#include "command_line.hpp"

#include "material/material.hpp"
#include "provenance/provenance.hpp"
#include "solver/solver_spec.hpp"

#include <CLI/CLI.hpp>
#include <fmt/core.h>
#include <fmt/ranges.h>

#include <sstream>
#include <string>
#include <vector>

namespace hofem::cli {

int parse_command_line(int argc, const char* const* argv, CommandLine& out, std::FILE* out_stream,
                       std::FILE* err_stream) {
  CLI::App app{"hofem: verification and benchmark harness for high-order FEM of deformable solids"};
  app.require_subcommand(1);
  app.set_help_all_flag("--help-all", "Help for every subcommand");
  app.set_version_flag("--version", version_text(), "Print hofem's version, commit, build type and compiler");

  auto& qo = out.quadrature;
  auto* quad = app.add_subcommand("quadrature", "Print the quadrature rule for a cell and degree");
  quad->add_option("--cell", qo.cell, "segment, triangle, tet, quad or hex")->required();
  quad->add_option("--degree", qo.degree, "Degree of exactness wanted (>= 0)");
  quad->add_flag("--json", qo.json, "Print JSON {cell, degree, source, points, weights}");
  quad->add_flag("--list", qo.list, "List every tabulated rule of the cell instead");

  auto& bo = out.basis;
  auto* basis = app.add_subcommand("basis", "Print the nodes of a Lagrange element (Gmsh order)");
  basis->add_option("--cell", bo.cell, "segment, triangle, tet or hex")->required();
  basis->add_option("--order", bo.order, "Polynomial order (>= 1; hex: 1 = Hex8, 2 = Hex20)")->required();
  basis->add_flag("--json", bo.json, "Print JSON");

  auto& meo = out.mesh;
  auto* mesh = app.add_subcommand("mesh", "Build or read a mesh, report its element quality, optionally write VTU");
  mesh->add_option("--box", meo.box, "Unit cube with N cells per side");
  mesh->add_option("--msh", meo.msh, "Gmsh .msh file (4.1 or 2.2 ASCII)");
  mesh->add_option("--cell", meo.cell, "Box mesh cells: tet or hex")->capture_default_str();
  mesh->add_option("--order", meo.order, "Element order (box: any for tet, 1-2 for hex; msh: raise a linear mesh to it)");
  mesh->add_option("--vtu", meo.vtu, "Write the mesh to this .vtu file");
  const std::string vtu_format_help =
      "Encoding of the .vtu files: ascii (text), binary (appended raw, ~2x smaller) or zlib (appended, compressed)";
  const auto vtu_formats = CLI::IsMember({"ascii", "binary", "zlib"});
  mesh->add_option("--vtu-format", meo.vtu_format, vtu_format_help)->check(vtu_formats)->capture_default_str();
  mesh->add_flag("--json", meo.json, "Print JSON");
  mesh->add_option("--partition", meo.partition, "Partition into K parts (recursive coordinate bisection) and report their quality");

  auto& mo = out.mms;
  auto* mms = app.add_subcommand("mms", "Solve a manufactured-solution problem on the unit cube and print its errors");
  mms->add_option("--problem", mo.problem,
                  fmt::format("The material of the manufactured problem ({}); linear: one linear solve of linear "
                              "elasticity at displacement scale 1, the others Newton at scale 0.1",
                              fmt::join(material_names(), ", ")))
      ->required();
  mms->add_option("--order", mo.order,
                  "Element order (tet: >= 1; hex: 1 = Hex8, 2 = Hex20), or a comma list (1,2,3): every order x n "
                  "combination runs, printed as a table with observed rates (--json: one JSON object per line)")
      ->required();
  mms->add_option("--n", mo.n, "Cubes per side (>= 1), or a comma list (2,4,8)")->required();
  mms->add_option("--cell", mo.cell, "tet or hex")->capture_default_str();
  mms->add_flag("--perturbed", mo.perturbed, "Randomly perturb interior vertices (non-uniform mesh)");
  mms->add_option("--solver", mo.solver,
                  "Linear solver (auto: the fastest for the system, with a tolerance tied to the discretisation "
                  "error): " + linear_solver_choices())
      ->capture_default_str();
  mms->add_flag("--json", mo.json, "Print JSON");
  mms->add_flag("--distributed", mo.distributed,
                "Partition the elements over the MPI ranks and solve on hypre (mpirun -np K hofem mms ...; rank 0 prints)");
  mms->add_option("--vtu", mo.vtu, "Write the solution (displacement, exact displacement, L2 error per cell) to this .vtu");
  mms->add_option("--vtu-format", mo.vtu_format, vtu_format_help)->check(vtu_formats)->capture_default_str();
  mms->add_option("--export-matrix", mo.export_matrix,
                  "Write the solved linear system as MatrixMarket: PREFIX.mtx (K), PREFIX_rhs.mtx, PREFIX_solution.mtx");
  mms->add_option("--krylov", mo.krylov, "With --distributed: hypre's pcg or gmres")->capture_default_str();
  mms->add_option("--amg", mo.amg, "With --distributed: BoomerAMG variant (amg, amg-nodal, amg-aggressive)")
      ->capture_default_str();
  mms->add_flag("--rigid-body-modes", mo.rigid_body_modes,
                "With --distributed: rigid rotations as BoomerAMG interpolation vectors (nodal coarsening)");

  auto& vo = out.verify;
  auto* verify = app.add_subcommand("verify", "Run the verification suite and write its JSON report");
  verify->add_option("--out", vo.out, "Report path")->capture_default_str();
  verify->add_option("--group", vo.group,
                     "Run only the checks whose groups start with this prefix (e.g. quadrature, embedded, mms.rate_h1) "
                     "and report only their rows");
  verify->add_flag("--quiet", vo.quiet, "Print only the summary line (progress lines on stderr stay: HOFEM_PROGRESS=0)");
  verify->add_option("--junit", vo.junit, "Also write the checks as JUnit XML to this file (one testcase per check)");
  verify->add_flag("--list", vo.list, "List the families of checks (id, ctest label, groups) and exit");
  verify->add_option("--convergence", vo.convergence, "Manufactured-solution study: none, ci or full")->capture_default_str();
  verify->add_option("--convergence-table", vo.convergence_table,
                     "Write the study's table (a row per run: errors, rates, unknowns, seconds, iterations) to "
                     "PREFIX.csv and PREFIX.json (default: convergence.* beside --out)");

  auto& ro = out.run;
  auto* run = app.add_subcommand("run", "Run a scene file: VTU frames, a .pvd index and stats.json into --out");
  // SCENE and --out are required by scene_commands.cpp: --print-defaults needs neither, --check no --out.
  run->add_option("scene", ro.scene, "Scene file (JSON; scripts/scenes/ has the built-in ones; SCENE_FORMAT.md)");
  run->add_option("--out", ro.out, "Output directory (required unless --check or --print-defaults)");
  run->add_option("--set", ro.set,
                  "Override a scene key before validation: key.path=VALUE, VALUE JSON or a bare string "
                  "(mesh.order=2, boundary.0.release=1.5; repeatable; as a study's overrides)")
      ->allow_extra_args(false);
  run->add_flag("--check", ro.check, "Validate the scene (with --set) and build its meshes, print 'SCENE: valid'; no run");
  run->add_flag("--print-defaults", ro.print_defaults, "Print a scene with every key at its default (JSON) and exit");
  run->add_flag("--no-frames", ro.no_frames, "Write stats.json only");
  run->add_flag("--final-frame", ro.final_frame,
                "With --no-frames: still write the last state as final.vtu (final_surface.vtu when embedded)");
  run->add_option("--vtu-format", ro.vtu_format, vtu_format_help)->check(vtu_formats)->capture_default_str();
  run->add_option("--checkpoint-every", ro.checkpoint_every,
                  "Time-stepping runs: a checkpoint in OUT/checkpoint/ every N steps ('25') or seconds ('60s'), "
                  "written atomically, for --resume");
  run->add_flag("--resume", ro.resume,
                "Continue from OUT/checkpoint/ when it holds a checkpoint of this scene (else start from rest); "
                "checkpoints go on every 60 s unless --checkpoint-every says otherwise");
  run->add_option("--save-state", ro.save_state, "Time-stepping runs: write the last state reached to this state file");
  run->add_flag("--distributed", ro.distributed,
                "Partition the elements over the MPI ranks (static and implicit-Euler scenes; mpirun -np K; rank 0 writes)");

  auto& so = out.study;
  auto* study = app.add_subcommand("study", "Run a study: a scene's discretisations against a reference, time against error");
  study->add_option("study", so.study, "Study file (JSON; scripts/studies/ has the built-in ones)")->required();
  study->add_option("--out", so.out, "Output directory (default: reports/studies/NAME)");
  study->add_flag("--resume", so.resume,
                  "Keep each finished run's record under OUT/runs/NAME and reuse it when the run's scene is unchanged; "
                  "a run stopped part-way continues from its checkpoint (every 120 s)");
  study->add_flag("--extended", so.extended,
                  "Run the runs marked \"extended\" too (the costliest rungs; without it they are reported only from a "
                  "stored measurement)");

  auto* choices = app.add_subcommand("choices", "List what a scene or command can name: materials, integrators, "
                                                "linear solvers, preconditioners, element orders (from their registries)");
  choices->add_flag("--json", out.choices.json, "Print JSON");

  // Input caps (io/input_file.hpp), raised per run; validated in commands.cpp.
  const std::string limit_help = "Raise an input cap: NAME=VALUE, NAME one of mesh-file-mb, scene-file-kb, elements, "
                                 "nodes, order, json-depth, boundary-entries (repeatable; README: input caps)";
  mesh->add_option("--limit", out.mesh.limits, limit_help)->allow_extra_args(false);
  mms->add_option("--limit", out.mms.limits, limit_help)->allow_extra_args(false);
  run->add_option("--limit", out.run.limits, limit_help)->allow_extra_args(false);
  study->add_option("--limit", out.study.limits, limit_help)->allow_extra_args(false);
  const std::string reorient_help =
      "Renumber straight inverted elements of the .msh (left-handed node order) and warn; curved or folded ones stay errors";
  mesh->add_flag("--reorient", out.mesh.reorient, reorient_help);
  run->add_flag("--reorient", out.run.reorient, reorient_help);

  // CLI11 reports an unknown first word as "a subcommand is required"; name it instead.
  if (argc > 1 && argv[1][0] != '-') {
    const std::string first = argv[1];
    bool known = false;
    std::vector<std::string> valid;
    for (const auto* sub : app.get_subcommands({})) {
      known = known || sub->get_name() == first;
      valid.push_back(sub->get_name());
    }
    if (!known) {
      fmt::print(err_stream, "hofem: error: unknown subcommand '{}' (valid: {})\n", first, fmt::join(valid, ", "));
      return 2;
    }
  }
  // CLI11 prints help to a std::ostream; pass it on to the caller's stream.
  const auto print_help = [&](const CLI::Error& e) {
    std::ostringstream help, err;
    const int status = app.exit(e, help, err);
    std::fputs(help.str().c_str(), out_stream);
    std::fputs(err.str().c_str(), err_stream);
    return status;
  };
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return print_help(e);
  } catch (const CLI::CallForAllHelp& e) {
    return print_help(e);
  } catch (const CLI::CallForVersion& e) {
    return print_help(e);
  } catch (const CLI::ParseError& e) {
    std::string what = e.what();
    if (what.empty()) what = e.get_name();
    fmt::print(err_stream, "hofem: error: {} (run 'hofem --help')\n", what);
    return 2;
  }

  for (const auto* sub : app.get_subcommands({}))
    if (*sub) out.subcommand = sub->get_name();
  return -1;
}

}  // namespace hofem::cli
