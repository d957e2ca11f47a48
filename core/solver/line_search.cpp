#include "solver/line_search.hpp"

#include <cmath>
#include <limits>

namespace hofem {

LineSearchResult armijo_backtracking(NonlinearProblem& problem, const Eigen::VectorXd& u, const Eigen::VectorXd& d,
                                     double E, double slope, double residual, const NewtonOptions& opt,
                                     Eigen::VectorXd& u_trial, Eigen::VectorXd& g_trial) {
  LineSearchResult r;
  double alpha = 1.0;
  for (int b = 0; b <= opt.max_backtracks; ++b, alpha *= 0.5) {
    u_trial = u + alpha * d;
    const double E_new = problem.energy(u_trial);
    if (!std::isfinite(E_new)) continue;
    const double rounding = 64.0 * std::numeric_limits<double>::epsilon() * (std::fabs(E) + std::fabs(E_new));
    if (E_new <= E + opt.armijo * alpha * slope) {
      r.accepted = true;
    } else if (std::fabs(E_new - E) <= rounding) {
      problem.gradient(u_trial, g_trial);
      r.accepted = r.gradient_known = problem.norm(g_trial) < residual;
    }
    if (r.accepted) {
      r.step = alpha;
      r.energy = E_new;
      return r;
    }
  }
  return r;
}

}  // namespace hofem
