#pragma once
// The backtracking Armijo line search of newton_minimize (solver/newton.hpp).
#include "solver/newton.hpp"

#include <Eigen/Core>

namespace hofem {

struct LineSearchResult {
  bool accepted = false;
  double step = 1.0;             ///< the accepted step length alpha
  double energy = 0.0;           ///< E(u + alpha d) when accepted
  bool gradient_known = false;   ///< g_trial holds the gradient at the accepted point
};

/// Halves alpha from 1 (at most opt.max_backtracks times) until
/// E(u + alpha d) <= E + opt.armijo alpha slope. Near convergence the energy
/// decrease drops below the rounding of E itself; a step that changes E by no
/// more than that rounding (64 eps (|E| + |E_new|)) is accepted if it reduces
/// the gradient's norm below `residual` (g_trial is then that gradient).
/// u_trial holds the last point tried (the accepted one when accepted).
LineSearchResult armijo_backtracking(NonlinearProblem& problem, const Eigen::VectorXd& u, const Eigen::VectorXd& d,
                                     double E, double slope, double residual, const NewtonOptions& opt,
                                     Eigen::VectorXd& u_trial, Eigen::VectorXd& g_trial);

}  // namespace hofem
