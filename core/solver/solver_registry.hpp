#pragma once
// The one list of hofem's linear solvers and preconditioners: each name, what
// it is and what it needs. The scene reader and the command line validate
// names with it; --help, the scene schema, SCENE_FORMAT.md, the solver sweep
// and the benchmarks list it (ctest registries.lists_agree); and
// solver_factory.cpp makes a solver of each row (one case per kind). It holds
// no solver itself, so that the sanitized input tests
// (verification/unit/CMakeLists.txt) link it without hypre or CHOLMOD.
// Adding a preconditioner: its file, a row in solver_registry.cpp, a case in
// solver_factory.cpp (-Wswitch names a kind without one), its tests.
#include "linalg/solver_method.hpp"

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace hofem {

enum class PreconditionerKind { Identity, Jacobi, BlockJacobi, Ic0, EigenIct, BoomerAmg, PMultigrid, Schwarz };

struct PreconditionerEntry {
  std::string_view name;
  std::string_view description;
  PreconditionerKind kind;
  /// Needs the mesh and DOF map (set_mesh_view) before its set-up.
  bool needs_mesh_view = false;
};

struct LinearSolverEntry {
  SolverMethod method;
  std::string_view description;
  /// The preconditioners it takes: every registered one for our Krylov
  /// methods ("cg+pmg"), only "amg" for hypre's PCG, none for direct solvers.
  std::vector<std::string> preconditioners;
};

/// Every preconditioner, in the order the help texts list them (the BoomerAMG
/// variants of linalg/boomeramg_variants.hpp among them).
std::span<const PreconditionerEntry> preconditioner_registry();
/// The row of a name, or nullptr.
const PreconditionerEntry* find_preconditioner(std::string_view name);
std::vector<std::string> preconditioner_names();
/// True for preconditioners that need set_mesh_view() before setup().
bool preconditioner_needs_mesh_view(std::string_view name);

/// Every solver method with the preconditioners it takes.
std::span<const LinearSolverEntry> linear_solver_registry();
/// Every name SolverSpec::parse accepts but "auto": the direct solvers, hypre's
/// PCG and each Krylov method with each preconditioner.
std::vector<std::string> linear_solver_names();
/// The same in one line for help texts and errors:
/// "auto, cholmod, ..., or <cg|cr|minres|gmres>+<none|jacobi|...>".
std::string linear_solver_choices();

}  // namespace hofem
