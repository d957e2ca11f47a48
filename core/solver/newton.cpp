#include "solver/newton.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>

namespace hofem {

namespace {

// Adds s to the diagonal of K (all diagonal entries exist in an FE pattern).
void shift_diagonal(SparseMatrix& K, double s) {
  for (Eigen::Index c = 0; c < K.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(K, c); it; ++it)
      if (it.row() == c) it.valueRef() += s;
}

double mean_abs_diagonal(const SparseMatrix& K) {
  double sum = 0.0;
  for (Eigen::Index c = 0; c < K.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(K, c); it; ++it)
      if (it.row() == c) sum += std::fabs(it.value());
  return K.rows() > 0 ? sum / static_cast<double>(K.rows()) : 1.0;
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
  for (int it = 0; it < opt.max_iterations; ++it) {
    NewtonIteration rec;
    rec.residual = g.norm();
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
      const double s = (shift == 0.0 ? 1e-8 : 10.0) * (shift == 0.0 ? mean_abs_diagonal(K) : shift);
      shift_diagonal(K, s - shift);
      shift = s;
      ok = solver.factorize(K);
    }
    if (!ok) {
      result.message = "could not make the Hessian positive definite";
      result.iterations = it;
      result.history.push_back(rec);
      return result;
    }
    rec.projected = project;
    rec.shift = shift;
    solver.solve(-g, d);
    const double slope = g.dot(d);
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
        if (g_new.norm() < rec.residual) {
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
  result.final_residual = g.norm();
  result.converged = result.final_residual <= tol;
  result.message = result.converged ? "converged at the iteration limit"
                                    : fmt::format("no convergence in {} iterations (|g| = {:.3e})", opt.max_iterations,
                                                  result.final_residual);
  return result;
}

}  // namespace hofem
