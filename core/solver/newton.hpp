#pragma once
// Damped Newton for minimising a smooth energy (thesis Algorithm 1): solve
// K d = -g, then backtracking (Armijo) line search on the energy.
//
// Stopping rule: ||g|| <= rtol * force_scale, where force_scale is a representative
// force of the problem (Longva et al. 2020 §6 stop when the residual falls below 1e-5
// of a representative force, M a_rep with gravity; for a static problem we use
// the external load and the first residual, see NonlinearProblem::force_scale).
// Indefinite Hessians: if the factorisation reports "not positive definite" the
// Hessian is rebuilt with per-point PSD projection of dP/dF and, failing that,
// shifted by a growing multiple of its diagonal scale.
#include "linalg/sparse_matrix.hpp"
#include "linalg/linear_solver.hpp"

#include <Eigen/Core>

#include <cmath>

#include <string>
#include <vector>

namespace hofem {

/// An energy over a vector of unknowns with gradient and sparse Hessian.
class NonlinearProblem {
 public:
  virtual ~NonlinearProblem() = default;
  virtual int size() const = 0;
  /// +infinity where the energy is not defined (inverted elements for some materials).
  virtual double energy(const Eigen::VectorXd& u) = 0;
  /// Returns the energy; fills g.
  virtual double gradient(const Eigen::VectorXd& u, Eigen::VectorXd& g) = 0;
  /// Fills g and K (same pattern every call). project: PSD projection per quadrature point.
  virtual void hessian(const Eigen::VectorXd& u, Eigen::VectorXd& g, SparseMatrix& K, bool project) = 0;
  /// Representative force magnitude for the relative stopping rule (> 0).
  virtual double force_scale(const Eigen::VectorXd& g0) const = 0;
  /// Inner product of two vectors of unknowns. A distributed problem
  /// holds each rank's unknowns plus ghost copies of its neighbours' and sums the
  /// owned entries over the ranks, so that every rank takes the same decisions.
  virtual double dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const { return a.dot(b); }
  double norm(const Eigen::VectorXd& a) const { return std::sqrt(dot(a, a)); }
};

struct NewtonOptions {
  int max_iterations = 50;
  double rtol = 1e-9;           ///< ||g|| <= rtol * force_scale
  bool project_psd = false;     ///< always project dP/dF (otherwise only after a failed factorisation)
  double armijo = 1e-4;         ///< sufficient decrease constant c in E(u + a d) <= E(u) + c a g.d
  int max_backtracks = 30;
  /// Inexact Newton (Eisenstat & Walker 1996, choice 2): an iterative linear
  /// solver is only asked for eta_k = gamma (|g_k| / |g_k-1|)^alpha relative
  /// residual, safeguarded, instead of a fixed tight tolerance. Direct solvers
  /// are unaffected.
  bool eisenstat_walker = false;
  double ew_gamma = 0.9, ew_alpha = 2.0;
  double ew_eta_max = 0.5;   ///< first and loosest forcing term
  double linear_rtol = 1e-8; ///< iterative solvers' tolerance without Eisenstat-Walker (and its floor)
};

struct NewtonIteration {
  double residual = 0.0;  ///< ||g|| before the step
  double energy = 0.0;
  double step = 0.0;      ///< accepted line-search step length
  bool projected = false;
  double shift = 0.0;     ///< diagonal shift used (0 if none)
  /// How the step direction was obtained: "newton" (the Hessian as assembled),
  /// "projected" (PSD-projected Hessian), "shifted" (a diagonal shift added) or
  /// "gradient" (steepest descent, when no Hessian gave a descent direction).
  std::string direction = "newton";
  double linear_rtol = 0.0;   ///< forcing term asked of an iterative solver (0: direct)
  int linear_iterations = 0;  ///< iterations of an iterative solver (0: direct)
};

struct NewtonResult {
  bool converged = false;
  int iterations = 0;
  double final_residual = 0.0;  ///< ||g|| where it stopped (converged or not)
  double force_scale = 0.0;     ///< 0 if it stopped before measuring one
  int linear_iterations = 0;  ///< summed over the iterations
  std::vector<NewtonIteration> history;
  std::string message;  ///< why it stopped
};

NewtonResult newton_minimize(NonlinearProblem& problem, Eigen::VectorXd& u, LinearSolver& solver,
                             const NewtonOptions& options);

/// How far the solve ended from its stopping rule: final_residual / (rtol *
/// force_scale), <= 1 exactly when it converged (the verification suite checks
/// this number instead of the flag). +inf when Newton stopped before it measured a
/// force scale (force_scale 0: the energy was undefined at the initial guess;
/// NonlinearProblem::force_scale is > 0 otherwise), NaN when the residual is.
double residual_over_tolerance(const NewtonResult& result, double rtol);

}  // namespace hofem
