// The Newton direction of newton_minimize: the Hessian made positive definite
// where it is not, the linear solve with its retry, and the descent check with
// its fallbacks (newton_direction.hpp).
#include "solver/newton_direction.hpp"

#include <cmath>
#include <stdexcept>

namespace hofem {

namespace {

// Adds s to the diagonal of K (all diagonal entries exist in an FE pattern).
void shift_diagonal(SparseMatrix& K, double s) {
  for (Eigen::Index c = 0; c < K.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(K, c); it; ++it)
      if (it.row() == c) it.valueRef() += s;
}

// Mean |K_ii| over the whole system: through the problem's dot product, so that
// on a distributed problem every rank shifts by the same amount (a rank-local
// mean would shift the ranks' rows differently and break the symmetry).
double mean_abs_diagonal(const NonlinearProblem& problem, const SparseMatrix& K) {
  const Eigen::VectorXd abs_diagonal = K.diagonal().cwiseAbs();
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(abs_diagonal.size());
  const double count = problem.dot(ones, ones);
  return count > 0.0 ? problem.dot(abs_diagonal, ones) / count : 1.0;
}

constexpr double kDescentCosine = 1e-12;

bool is_descent(const NonlinearProblem& problem, const Eigen::VectorXd& g, const Eigen::VectorXd& d) {
  const double slope = problem.dot(g, d);
  return std::isfinite(slope) && slope < 0.0 && slope <= -kDescentCosine * problem.norm(g) * problem.norm(d);
}

// The fallback chain of newton_minimize when the solver's direction is not a
// descent direction: projected Hessian, shifts growing tenfold from 1e-8 of the
// mean diagonal (up to 12), then d = -g scaled by the mean diagonal's inverse.
void descent_fallback(NonlinearProblem& problem, const Eigen::VectorXd& u, Eigen::VectorXd& g, SparseMatrix& K,
                      Eigen::VectorXd& d, LinearSolver& solver, bool& project, double& shift, NewtonIteration& rec) {
  auto try_solve = [&]() {
    try {
      if (!solver.factorize(K)) return false;
      solver.solve(-g, d);
    } catch (const std::runtime_error&) {
      return false;
    }
    return is_descent(problem, g, d);
  };
  if (!project) {
    project = true;
    shift = 0.0;
    problem.hessian(u, g, K, true);
    rec.projected = true;
    if (try_solve()) {
      rec.direction = "projected";
      return;
    }
  }
  const double base = mean_abs_diagonal(problem, K);
  for (int k = 0; k < 12; ++k) {
    const double s = (shift == 0.0 ? 1e-8 * base : 10.0 * shift);
    shift_diagonal(K, s - shift);
    shift = s;
    if (try_solve()) {
      rec.shift = shift;
      rec.direction = "shifted";
      return;
    }
  }
  rec.shift = shift;
  rec.direction = "gradient";
  d = -g / (base > 0.0 ? base : 1.0);
}

}  // namespace

bool factorize_hessian(NonlinearProblem& problem, const Eigen::VectorXd& u, Eigen::VectorXd& g, SparseMatrix& K,
                       LinearSolver& solver, DirectionState& state) {
  problem.hessian(u, g, K, state.project);
  bool ok = solver.factorize(K);
  if (!ok && !state.project) {
    state.project = true;
    problem.hessian(u, g, K, true);
    ok = solver.factorize(K);
  }
  for (int k = 0; !ok && k < 20; ++k) {  // projection is per point; the sum can still be singular
    const double s = (state.shift == 0.0 ? 1e-8 : 10.0) * (state.shift == 0.0 ? mean_abs_diagonal(problem, K) : state.shift);
    shift_diagonal(K, s - state.shift);
    state.shift = s;
    ok = solver.factorize(K);
  }
  return ok;
}

std::string solve_direction(NonlinearProblem& problem, const Eigen::VectorXd& u, Eigen::VectorXd& g, SparseMatrix& K,
                            LinearSolver& solver, DirectionState& state, Eigen::VectorXd& d) {
  // An iterative solver can fail where a factorisation would not (CG meeting
  // negative curvature on an indefinite Hessian): retry once on the projected
  // Hessian, which is positive semi-definite by construction.
  for (bool retry = false;; retry = true) {
    try {
      if (retry && !solver.factorize(K)) throw std::runtime_error("projected Hessian rejected by the solver");
      solver.solve(-g, d);
      return {};
    } catch (const std::runtime_error& e) {
      if (retry || state.project) return e.what();
    }
    state.project = true;
    problem.hessian(u, g, K, true);
  }
}

void ensure_descent(NonlinearProblem& problem, const Eigen::VectorXd& u, Eigen::VectorXd& g, SparseMatrix& K,
                    Eigen::VectorXd& d, LinearSolver& solver, DirectionState& state, NewtonIteration& rec) {
  // Sufficient descent, g.d <= -c |g| |d|: an indefinite-capable solver (CR,
  // MINRES, GMRES, UMFPACK, LDL^T) returns an ascent direction on an indefinite
  // Hessian, and with a positive slope the Armijo test would admit an energy
  // increase. c = 1e-12 lies below 1/cond(K) for any Hessian this code
  // factorises, so a true Newton direction on a positive definite Hessian
  // (cos angle >= 1/cond) always passes. Otherwise fall back, as trust-region
  // free Newton codes do: the projected Hessian, then growing diagonal shifts,
  // then the gradient; the iteration records which.
  rec.direction = state.shift > 0.0 ? "shifted" : state.project ? "projected" : "newton";
  if (!is_descent(problem, g, d)) descent_fallback(problem, u, g, K, d, solver, state.project, state.shift, rec);
}

}  // namespace hofem
