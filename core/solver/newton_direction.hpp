#pragma once
// The Newton direction of newton_minimize (solver/newton.hpp), in three steps
// that each iteration takes in order: factorize_hessian, solve_direction,
// ensure_descent. Each fallback they take (projection per quadrature point,
// diagonal shifts, the gradient) is kept in DirectionState and recorded in the
// iteration's NewtonIteration.
#include "linalg/sparse_matrix.hpp"
#include "linalg/linear_solver.hpp"
#include "solver/newton.hpp"

#include <Eigen/Core>

#include <string>

namespace hofem {

/// How the direction of one Newton iteration was obtained so far.
struct DirectionState {
  bool project = false;  ///< the Hessian is projected onto PSD per quadrature point
  double shift = 0.0;    ///< diagonal shift added to it
};

/// The Hessian at u (projected if state.project), factorised; if the solver
/// refuses it, the projected Hessian, then diagonal shifts from 1e-8 of the mean
/// |K_ii| growing tenfold (up to 20). False if none is accepted.
bool factorize_hessian(NonlinearProblem& problem, const Eigen::VectorXd& u, Eigen::VectorXd& g, SparseMatrix& K,
                       LinearSolver& solver, DirectionState& state);

/// d = -K^-1 g with the factorised K, retried once on the projected Hessian if
/// an iterative solver fails on the exact one. The failure message, or empty.
std::string solve_direction(NonlinearProblem& problem, const Eigen::VectorXd& u, Eigen::VectorXd& g, SparseMatrix& K,
                            LinearSolver& solver, DirectionState& state, Eigen::VectorXd& d);

/// Makes d a sufficient descent direction (g.d <= -1e-12 |g| |d|), falling back
/// to the projected Hessian, growing shifts and finally the scaled gradient;
/// records the kind in rec.direction (and rec.projected / rec.shift).
void ensure_descent(NonlinearProblem& problem, const Eigen::VectorXd& u, Eigen::VectorXd& g, SparseMatrix& K,
                    Eigen::VectorXd& d, LinearSolver& solver, DirectionState& state, NewtonIteration& rec);

}  // namespace hofem
