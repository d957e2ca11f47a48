#pragma once
// The linear-solver boundary: Newton and the time integrators see only this.
// A solver analyses a sparsity pattern once (symbolic factorisation, orderings),
// then factorises and solves many matrices with that pattern.
#include "linalg/sparse_matrix.hpp"

#include <Eigen/Core>

#include <string>
#include <string_view>

namespace hofem {

struct MeshView;  // assembly/mesh_view.hpp: passed on, never looked into (linalg/preconditioner.hpp)

/// The solvers: linalg/cholmod_solver.hpp, umfpack_solver.hpp,
/// eigen_ldlt_solver.hpp, krylov.hpp, hypre_pcg.hpp; made by name in
/// solver/solver_factory.cpp from the registry's names.
class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  virtual std::string_view name() const = 0;
  /// Symbolic analysis of A's pattern; called again only when the pattern changes.
  virtual void analyze(const SparseMatrix& A) = 0;
  /// Numeric factorisation (or set-up) for A. Returns false if A is not positive
  /// definite for a solver that needs it (the caller may then modify A and retry).
  virtual bool factorize(const SparseMatrix& A) = 0;
  /// x = A^-1 b with the last factorised A.
  virtual void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) = 0;
  /// Mesh and DOF map of the systems to come, for mesh-aware preconditioners.
  virtual void set_mesh_view(const MeshView&) {}
  /// Relative residual target of an iterative solver (Newton's inexact,
  /// Eisenstat-Walker tolerances); direct solvers ignore it.
  virtual void set_relative_tolerance(double) {}
  /// k > 0: every solve runs exactly k iterations of an iterative solver and
  /// returns that iterate, converged or not - a fixed work budget per solve (the
  /// thesis §5.3.2, Fig. 12: "3 iterations CG, 3 iterations PCR, 12 iterations
  /// CG"); k <= 0 restores convergence to the tolerance. Returns false for a
  /// solver that has no iterations to fix (direct solvers).
  virtual bool set_fixed_iterations(int) { return false; }
  virtual bool is_iterative() const { return false; }
  /// Iterations of the last solve (0 for direct solvers).
  virtual int last_iterations() const { return 0; }
  /// Why the last factorize() returned false, when the solver knows more than
  /// "not positive definite" (e.g. a preconditioner that cannot apply here).
  virtual std::string last_error() const { return {}; }
  /// Number of symbolic analyses / numeric factorisations (an iterative
  /// solver's preconditioner set-ups) done, and the matrices an iterative
  /// solver took without a set-up of their own, keeping the last one
  /// (KrylovOptions::setup_reuse). Run statistics.
  int analyses() const { return analyses_; }
  int factorizations() const { return factorizations_; }
  int setup_reuses() const { return setup_reuses_; }
  /// Wall seconds spent in numeric factorisations / preconditioner set-ups
  /// (CHOLMOD and the Krylov solvers count them; others report 0).
  double setup_seconds() const { return setup_seconds_; }

 protected:
  int analyses_ = 0;
  int factorizations_ = 0;
  int setup_reuses_ = 0;
  double setup_seconds_ = 0.0;
};

/// k > 0: solver.set_fixed_iterations(k), or std::invalid_argument naming the
/// solver if it has no iterations to fix.
void apply_iteration_budget(LinearSolver& solver, int k);
}  // namespace hofem
