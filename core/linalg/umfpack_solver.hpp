#pragma once
// Sparse LU through UMFPACK's long-integer interface (umfpack_dl_*): the
// symbolic analysis (column ordering) is done once per pattern and reused by
// every numeric factorisation. Works for any nonsingular matrix, SPD or not, so
// it is the direct fallback for indefinite Hessians; for SPD ones CHOLMOD is faster.
#include "linalg/linear_solver.hpp"
#include "linalg/solver_method.hpp"

namespace hofem {

class UmfpackSolver final : public LinearSolver {
 public:
  UmfpackSolver() = default;
  ~UmfpackSolver() override;
  UmfpackSolver(const UmfpackSolver&) = delete;
  UmfpackSolver& operator=(const UmfpackSolver&) = delete;

  std::string_view name() const override { return method_name(SolverMethod::Umfpack); }
  void analyze(const SparseMatrix& A) override;
  /// Returns false if A is singular (UMFPACK_WARNING_singular_matrix).
  bool factorize(const SparseMatrix& A) override;
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override;

 private:
  void free_numeric();
  void* symbolic_ = nullptr;
  void* numeric_ = nullptr;
  const SparseMatrix* A_ = nullptr;
  std::uint64_t pattern_ = 0;  // pattern_fingerprint of the analysed matrix
  double factor_flops_ = 0.0, solve_flops_ = 0.0;  // estimates of the analysis: how many BLAS threads pay
};

}  // namespace hofem
