#pragma once
// A linear solver as a value: its method, its preconditioner, a fixed Krylov
// budget and the options of the distributed (hypre) solver. Parsed and
// validated once - from the command line's "cg+pmg", a scene's "solver" object
// or a benchmark's name - and then carried by the problems (StaticOptions,
// DynamicsOptions), resolved ("auto", solver_choice.hpp) and made
// (make_linear_solver) without parsing a name again.
#include "linalg/solver_method.hpp"
#include "solver/solver_registry.hpp"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace hofem {

/// hypre's own Krylov method and BoomerAMG, used by every distributed solve.
struct DistributedSolverOptions {
  std::string krylov = "pcg";  ///< "pcg" (symmetric positive definite systems) or "gmres"
  std::string amg = "amg";     ///< a BoomerAMG variant (linalg/boomeramg_variants.hpp)
  /// Rigid rotations as BoomerAMG interpolation vectors (GM-2 with nodal
  /// coarsening, boomeramg.cpp measured its trade-off: fewer iterations, dearer
  /// set-up and cycles). Needs the node coordinates (set_coordinates).
  bool rigid_body_modes = false;
  int gmres_restart = 50;
};

/// Throws std::invalid_argument naming the bad option.
void validate(const DistributedSolverOptions& options);

struct SolverSpec {
  /// Empty: "auto", the fastest solver measured for the system (solver_choice.hpp).
  std::optional<SolverMethod> method;
  /// Krylov methods and hypre-pcg: a preconditioner_names() entry; else empty.
  std::string preconditioner;
  /// Krylov methods: tolerance, iteration limit, GMRES restart.
  KrylovOptions krylov;
  /// > 0: every solve runs exactly this many Krylov iterations and takes the
  /// iterate (LinearSolver::set_fixed_iterations); Krylov methods only.
  int fixed_iterations = 0;
  DistributedSolverOptions distributed;

  /// "auto", "cholmod", "cg+pmg", ...: what parse() reads back.
  std::string name() const;
  bool is_auto() const { return !method.has_value(); }
  /// Our Krylov methods (cg, cr, minres, gmres) with a preconditioner.
  bool is_krylov() const { return method && is_krylov_method(*method); }
  /// The sparse direct solvers (cholmod, umfpack, eigen-ldlt).
  bool is_direct() const { return method && is_direct_method(*method); }

  /// "auto" or a linear_solver_names() entry (solver/solver_registry.hpp);
  /// throws std::invalid_argument naming the valid choices.
  static SolverSpec parse(std::string_view name);
};

}  // namespace hofem
