#include "solver/newton.hpp"

#include "solver/line_search.hpp"
#include "solver/newton_direction.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>

namespace hofem {

namespace {

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

// HOFEM_NEWTON_TRACE=1: one line per Newton iteration on stderr (residual,
// direction, linear iterations, step), for diagnosing a slow step of a long
// run without a debugger. Read once; off unless set.
bool trace_enabled() {
  static const bool on = [] {
    const char* env = std::getenv("HOFEM_NEWTON_TRACE");
    return env != nullptr && std::strcmp(env, "0") != 0;
  }();
  return on;
}

void trace(int it, const NewtonIteration& rec, double tol, const std::string& note) {
  if (!trace_enabled()) return;
  fmt::print(stderr, "newton {:3d}: |g| = {:.3e} (tol {:.3e}) {} linear {} step {:.3g} shift {:.2e}{}{}\n", it,
             rec.residual, tol, rec.direction, rec.linear_iterations, rec.step, rec.shift, note.empty() ? "" : ": ",
             note);
  std::fflush(stderr);
}

}  // namespace

NewtonResult newton_minimize(NonlinearProblem& problem, Eigen::VectorXd& u, LinearSolver& solver,
                             const NewtonOptions& opt) {
  NewtonResult result;
  Eigen::VectorXd g, d, u_trial, g_trial;
  SparseMatrix K;
  double E = problem.gradient(u, g);
  if (!std::isfinite(E)) {
    result.message = "energy undefined at the initial guess (inverted elements?)";
    return result;
  }
  result.force_scale = problem.force_scale(g);
  const double tol = opt.rtol * result.force_scale;
  double g_prev = 0.0, eta = 0.0;
  // Ends the iteration `it` unconverged with `message`, recording it.
  const auto fail = [&](int it, NewtonIteration& rec, std::string message) {
    trace(it, rec, tol, message);
    result.message = std::move(message);
    result.final_residual = rec.residual;
    result.iterations = it;
    result.history.push_back(rec);
    return result;
  };
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
    // The direction (newton_direction.hpp).
    DirectionState state{opt.project_psd, 0.0};
    if (!factorize_hessian(problem, u, g, K, solver, state)) {
      // A preconditioner that cannot apply at all (pmg on order 1) fails every
      // shift too; its reason is what the user needs.
      const std::string why = solver.last_error();
      return fail(it, rec, "could not make the Hessian positive definite" +
                               (why.empty() ? std::string() : fmt::format(" (solver {}: {})", solver.name(), why)));
    }
    rec.shift = state.shift;
    if (solver.is_iterative()) {
      eta = forcing_term(opt, it, rec.residual, g_prev, eta, tol);
      solver.set_relative_tolerance(eta);
      rec.linear_rtol = eta;
    }
    const std::string solve_error = solve_direction(problem, u, g, K, solver, state, d);
    rec.projected = state.project;
    rec.linear_iterations = solver.last_iterations();
    result.linear_iterations += rec.linear_iterations;
    if (!solve_error.empty()) return fail(it, rec, fmt::format("linear solve failed at iteration {}: {}", it, solve_error));
    g_prev = rec.residual;
    ensure_descent(problem, u, g, K, d, solver, state, rec);
    // The step (line_search.hpp).
    const LineSearchResult step =
        armijo_backtracking(problem, u, d, E, problem.dot(g, d), rec.residual, opt, u_trial, g_trial);
    if (!step.accepted)
      return fail(it, rec, fmt::format("line search failed at iteration {} (|g| = {:.3e})", it, rec.residual));
    rec.step = step.step;
    trace(it, rec, tol, "");
    result.history.push_back(rec);
    u = u_trial;
    if (step.gradient_known) {  // the line search already evaluated the gradient here
      E = step.energy;
      g.swap(g_trial);
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

double residual_over_tolerance(const NewtonResult& result, double rtol) {
  if (!(result.force_scale > 0.0)) return std::numeric_limits<double>::infinity();
  return result.final_residual / (rtol * result.force_scale);
}

}  // namespace hofem
