#include "solver/newton.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
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

// Forcing term of Eisenstat & Walker (1996), choice 2, with their safeguard
// (do not drop faster than gamma eta_prev^alpha while that is above 0.1) and
// Kelley's (1995) floor: no point solving much below what the Newton stopping
// rule needs, 0.5 tol / |g|.
double forcing_term(const NewtonOptions& opt, int it, double g_norm, double g_prev, double eta_prev, double tol) {
  if (!opt.eisenstat_walker) return opt.linear_rtol;
  double eta = opt.ew_eta_max;
  if (it > 0) {
    eta = opt.ew_gamma * std::pow(g_norm / g_prev, opt.ew_alpha);
    const double safeguard = opt.ew_gamma * std::pow(eta_prev, opt.ew_alpha);
    if (safeguard > 0.1) eta = std::max(eta, safeguard);
  }
  eta = std::max(eta, 0.5 * tol / g_norm);
  return std::clamp(eta, opt.linear_rtol, opt.ew_eta_max);
}

}  // namespace

NewtonResult newton_minimize(NonlinearProblem& problem, Eigen::VectorXd& u, LinearSolver& solver,
                             const NewtonOptions& opt) {
  NewtonResult result;
  Eigen::VectorXd g, d, u_trial;
  SparseMatrix K;
  double E = problem.gradient(u, g);
  if (!std::isfinite(E)) {
    result.message = "energy undefined at the initial guess (inverted elements?)";
    return result;
  }
  result.force_scale = problem.force_scale(g);
  const double tol = opt.rtol * result.force_scale;
  double g_prev = 0.0, eta = 0.0;
  for (int it = 0; it < opt.max_iterations; ++it) {
    NewtonIteration rec;
    rec.residual = problem.norm(g);
    rec.energy = E;
    if (rec.residual <= tol) {
      result.converged = true;
      result.final_residual = rec.residual;
      result.iterations = it;
      result.message = fmt::format("converged: |g| = {:.3e} <= {:.1e} * {:.3e}", rec.residual, opt.rtol, result.force_scale);
      return result;
    }
    // Newton direction, making the Hessian positive definite if it is not.
    bool project = opt.project_psd;
    problem.hessian(u, g, K, project);
    bool ok = solver.factorize(K);
    if (!ok && !project) {
      project = true;
      problem.hessian(u, g, K, true);
      ok = solver.factorize(K);
    }
    double shift = 0.0;
    for (int k = 0; !ok && k < 20; ++k) {  // projection is per point; the sum can still be singular
      const double s = (shift == 0.0 ? 1e-8 : 10.0) * (shift == 0.0 ? mean_abs_diagonal(problem, K) : shift);
      shift_diagonal(K, s - shift);
      shift = s;
      ok = solver.factorize(K);
    }
    if (!ok) {
      // A preconditioner that cannot apply at all (pmg on order 1) fails every
      // shift too; its reason is what the user needs.
      const std::string why = solver.last_error();
      result.message = "could not make the Hessian positive definite" +
                       (why.empty() ? std::string() : fmt::format(" (solver {}: {})", solver.name(), why));
      result.iterations = it;
      result.history.push_back(rec);
      return result;
    }
    rec.shift = shift;
    if (solver.is_iterative()) {
      eta = forcing_term(opt, it, rec.residual, g_prev, eta, tol);
      solver.set_relative_tolerance(eta);
      rec.linear_rtol = eta;
    }
    // An iterative solver can fail where a factorisation would not (CG meeting
    // negative curvature on an indefinite Hessian): retry once on the projected
    // Hessian, which is positive semi-definite by construction.
    std::string solve_error;
    try {
      solver.solve(-g, d);
    } catch (const std::runtime_error& e) {
      solve_error = e.what();
    }
    if (!solve_error.empty() && !project) {
      project = true;
      problem.hessian(u, g, K, true);
      solve_error.clear();
      try {
        if (!solver.factorize(K)) throw std::runtime_error("projected Hessian rejected by the solver");
        solver.solve(-g, d);
      } catch (const std::runtime_error& e) {
        solve_error = e.what();
      }
    }
    rec.projected = project;
    rec.linear_iterations = solver.last_iterations();
    result.linear_iterations += rec.linear_iterations;
    if (!solve_error.empty()) {
      result.message = fmt::format("linear solve failed at iteration {}: {}", it, solve_error);
      result.iterations = it;
      result.history.push_back(rec);
      return result;
    }
    g_prev = rec.residual;
    // Sufficient descent, g.d <= -c |g| |d|: an indefinite-capable solver (CR,
    // MINRES, GMRES, UMFPACK, LDL^T) returns an ascent direction on an indefinite
    // Hessian, and with a positive slope the Armijo test below would admit an
    // energy increase. c = 1e-12 lies below 1/cond(K) for any Hessian this code
    // factorises, so a true Newton direction on a positive definite Hessian
    // (cos angle >= 1/cond) always passes. Otherwise fall back, as trust-region
    // free Newton codes do: the projected Hessian, then growing diagonal shifts,
    // then the gradient; the iteration records which.
    rec.direction = shift > 0.0 ? "shifted" : project ? "projected" : "newton";
    if (!is_descent(problem, g, d)) descent_fallback(problem, u, g, K, d, solver, project, shift, rec);
    const double slope = problem.dot(g, d);
    // Backtracking Armijo line search. Near convergence the energy decrease drops
    // below the rounding of E itself; a step that changes E by no more than that
    // rounding is accepted if it reduces the gradient.
    double alpha = 1.0, E_new = E;
    Eigen::VectorXd g_new;
    bool accepted = false, have_g_new = false;
    for (int b = 0; b <= opt.max_backtracks; ++b, alpha *= 0.5) {
      u_trial = u + alpha * d;
      E_new = problem.energy(u_trial);
      if (!std::isfinite(E_new)) continue;
      const double rounding = 64.0 * std::numeric_limits<double>::epsilon() * (std::fabs(E) + std::fabs(E_new));
      if (E_new <= E + opt.armijo * alpha * slope) {
        accepted = true;
        break;
      }
      if (std::fabs(E_new - E) <= rounding) {
        problem.gradient(u_trial, g_new);
        if (problem.norm(g_new) < rec.residual) {
          accepted = have_g_new = true;
          break;
        }
      }
    }
    if (!accepted) {
      result.message = fmt::format("line search failed at iteration {} (|g| = {:.3e})", it, rec.residual);
      result.iterations = it;
      result.history.push_back(rec);
      return result;
    }
    rec.step = alpha;
    result.history.push_back(rec);
    u = u_trial;
    if (have_g_new) {  // the line search already evaluated the gradient here
      E = E_new;
      g.swap(g_new);
    } else {
      E = problem.gradient(u, g);
    }
  }
  result.iterations = opt.max_iterations;
  result.final_residual = problem.norm(g);
  result.converged = result.final_residual <= tol;
  result.message = result.converged ? "converged at the iteration limit"
                                    : fmt::format("no convergence in {} iterations (|g| = {:.3e})", opt.max_iterations,
                                                  result.final_residual);
  return result;
}

}  // namespace hofem
