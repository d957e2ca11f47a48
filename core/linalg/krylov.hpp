#pragma once
// Preconditioned Krylov solvers (thesis §3.2): conjugate gradients (Alg. 4),
// conjugate residuals (Alg. 5), MINRES (Paige & Saunders 1975) and restarted
// GMRES(m) (Alg. 6). Each stops on the relative residual ||b - A x|| / ||b||,
// caps its iterations, records the residual history, and reports a breakdown
// instead of returning garbage (CG meeting p^T A p <= 0 on an indefinite matrix).
#include "linalg/sparse_matrix.hpp"
#include "linalg/linear_operator.hpp"
#include "linalg/linear_solver.hpp"
#include "linalg/preconditioner.hpp"
#include "linalg/solver_method.hpp"

#include <Eigen/Core>

#include <memory>
#include <string>
#include <vector>

namespace hofem {

struct KrylovResult {
  bool converged = false;
  int iterations = 0;
  double relative_residual = 0.0;  ///< true residual ||b - A x|| / ||b|| at the end
  std::vector<double> history;  ///< relative residual per iteration (index 0: initial)
  std::string breakdown;        ///< non-empty if the method broke down (and why)
};

/// The methods on any operator (the assembled matrix, or its 3x3 block copy).
KrylovResult conjugate_gradient(const LinearOperator& A, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                const Preconditioner& M, const KrylovOptions& opt);
KrylovResult conjugate_residual(const LinearOperator& A, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                const Preconditioner& M, const KrylovOptions& opt);
KrylovResult minres(const LinearOperator& A, const Eigen::VectorXd& b, Eigen::VectorXd& x, const Preconditioner& M,
                    const KrylovOptions& opt);
KrylovResult gmres(const LinearOperator& A, const Eigen::VectorXd& b, Eigen::VectorXd& x, const Preconditioner& M,
                   const KrylovOptions& opt);

/// The same on an assembled matrix.
inline KrylovResult conjugate_gradient(const SparseMatrix& A, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                       const Preconditioner& M, const KrylovOptions& opt) {
  return conjugate_gradient(SparseMatrixOperator(A), b, x, M, opt);
}
inline KrylovResult conjugate_residual(const SparseMatrix& A, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                       const Preconditioner& M, const KrylovOptions& opt) {
  return conjugate_residual(SparseMatrixOperator(A), b, x, M, opt);
}
inline KrylovResult minres(const SparseMatrix& A, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                           const Preconditioner& M, const KrylovOptions& opt) {
  return minres(SparseMatrixOperator(A), b, x, M, opt);
}
inline KrylovResult gmres(const SparseMatrix& A, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                          const Preconditioner& M, const KrylovOptions& opt) {
  return gmres(SparseMatrixOperator(A), b, x, M, opt);
}

/// A LinearSolver running one Krylov method (SolverMethod::Cg, Cr, Minres or
/// Gmres) with one preconditioner; factorize() sets the preconditioner up (or
/// keeps the last set-up, KrylovOptions::setup_reuse), solve() iterates
/// from zero and throws std::runtime_error if it does not converge.
class KrylovSolver final : public LinearSolver {
 public:
  KrylovSolver(SolverMethod method, std::unique_ptr<Preconditioner> preconditioner, KrylovOptions options = {});
  std::string_view name() const override { return name_; }
  void analyze(const SparseMatrix& A) override;
  bool factorize(const SparseMatrix& A) override;
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override;
  void set_mesh_view(const MeshView& d) override { M_->set_mesh_view(d); }
  void set_relative_tolerance(double rtol) override { options_.rtol = rtol; }
  /// A fixed budget also ends set-up reuse: its trigger is the iteration count.
  bool set_fixed_iterations(int k) override {
    fixed_iterations_ = k > 0 ? k : 0;
    return true;
  }
  bool is_iterative() const override { return true; }
  int last_iterations() const override { return last_.iterations; }
  std::string last_error() const override { return M_->last_error(); }
  const KrylovResult& last_result() const { return last_; }
  const Preconditioner& preconditioner() const { return *M_; }

 private:
  SolverMethod method_;
  std::string name_;
  std::unique_ptr<Preconditioner> M_;
  KrylovOptions options_;
  const SparseMatrix* A_ = nullptr;
  /// A's 3x3 block copy, the operator of the iterations when A's size is a
  /// multiple of 3 (structure rebuilt only when A's pattern changes).
  BlockSparseMatrix<double> block_;
  bool use_block_ = false;
  int fixed_iterations_ = 0;  ///< > 0: set_fixed_iterations
  KrylovResult last_;
  // Set-up reuse (KrylovOptions::setup_reuse).
  bool reused_ = false;          ///< the preconditioner was set up for an earlier matrix
  bool rebuild_next_ = true;     ///< the next factorize() sets the preconditioner up
  int baseline_iterations_ = -1; ///< the first solve's iterations after the last set-up (-1: none yet)
  std::uint64_t setup_pattern_ = 0;  ///< pattern_fingerprint of the last matrix
  Eigen::Index setup_rows_ = -1;
  double last_setup_seconds_ = 0.0;   ///< S of the amortised rule (krylov.cpp)
  double setup_cost_iterations_ = 0.0;  ///< S / t: the last set-up in iterations of its first solve
  long long solves_since_setup_ = 0, extra_since_setup_ = 0;  ///< L and E of the amortised rule
  bool setup_preconditioner(const SparseMatrix& A);
  void iterate(const Eigen::VectorXd& b, Eigen::VectorXd& x);
};

}  // namespace hofem
