#pragma once
// A linear solver as a value: its method, its preconditioner, a fixed Krylov
// budget and the options of the distributed (hypre) solver. Parsed and
// validated once - from the command line's "cg+pmg", a scene's "solver" object
// or a benchmark's name - and then carried by the problems (StaticOptions,
// DynamicsOptions), resolved ("auto", solver_choice.hpp) and made
// (make_linear_solver) without parsing a name again.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace hofem {

enum class SolverMethod { Cholmod, Umfpack, EigenLdlt, HyprePcg, Cg, Cr, Minres, Gmres };

/// The name of a method as the command line spells it ("cholmod", "cg", ...).
std::string_view method_name(SolverMethod method);

/// When a Krylov solver keeps its preconditioner set-up for a new matrix of the
/// same pattern (Newton iterations, time steps), as PETSc's
/// -snes_lag_preconditioner_persists does with a fixed lag. A reused set-up is
/// a fixed SPD operator, so CG stays valid; it only costs iterations. A solve
/// that fails on a reused set-up is retried once on a fresh one.
enum class SetupReuse {
  Default,    ///< "auto" resolves it to Amortised; a named solver to Never
  Never,      ///< a set-up for every matrix
  Amortised,  ///< rebuilt when a stale solve costs more than the average since the set-up (krylov.cpp)
  Growth,     ///< rebuilt when a solve needs more than setup_reuse_growth x the first solve's iterations
};

/// The tolerances of our Krylov methods. Newton replaces rtol before each solve
/// (its linear tolerance or Eisenstat-Walker forcing term).
struct KrylovOptions {
  double rtol = 1e-8;        ///< converged when the true residual ||b - A x|| <= rtol ||b||
  int max_iterations = 5000;
  int restart = 50;          ///< GMRES(m)
  SetupReuse setup_reuse = SetupReuse::Default;
  double setup_reuse_growth = 1.5;  ///< SetupReuse::Growth's factor (>= 1)
};

/// hypre's own Krylov method and BoomerAMG, used by every distributed solve.
struct DistributedSolverOptions {
  std::string krylov = "pcg";  ///< "pcg" (symmetric positive definite systems) or "gmres"
  std::string amg = "amg";     ///< a boomeramg_variant_names() entry
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
  bool is_krylov() const;
  /// The sparse direct solvers (cholmod, umfpack, eigen-ldlt).
  bool is_direct() const;

  /// "auto" or a linear_solver_names() entry; throws std::invalid_argument
  /// naming the valid choices.
  static SolverSpec parse(std::string_view name);
};

/// Names of the BoomerAMG configurations offered as preconditioners and to the
/// distributed solver ("amg", ...; boomeramg.cpp defines them).
std::vector<std::string> boomeramg_variant_names();

/// The names SolverSpec::parse accepts, in one line for help texts and errors:
/// "auto, cholmod, ..., or <cg|cr|minres|gmres>+<none|jacobi|...>".
std::string linear_solver_choices();

/// Every name SolverSpec::parse accepts but "auto": the direct solvers, hypre's
/// PCG and each Krylov method with each preconditioner (solver_names.cpp).
std::vector<std::string> linear_solver_names();

}  // namespace hofem
