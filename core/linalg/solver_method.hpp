#pragma once
// The linear-solver methods linear algebra offers and the options of its
// Krylov methods, as values: what a LinearSolver is (solver/solver_spec.hpp
// adds the preconditioner's name and the parsing of "cg+pmg").
#include <optional>
#include <string_view>

namespace hofem {

enum class SolverMethod { Cholmod, Umfpack, EigenLdlt, HyprePcg, Cg, Cr, Minres, Gmres };

/// The name of a method as the command line spells it ("cholmod", "cg", ...).
std::string_view method_name(SolverMethod method);
/// The method of a name, or nothing.
std::optional<SolverMethod> method_named(std::string_view name);
/// Our Krylov methods (cg, cr, minres, gmres), which take a preconditioner.
bool is_krylov_method(SolverMethod method);
/// The sparse direct solvers (cholmod, umfpack, eigen-ldlt).
bool is_direct_method(SolverMethod method);

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

}  // namespace hofem
