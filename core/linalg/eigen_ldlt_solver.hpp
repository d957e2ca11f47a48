#pragma once
// Eigen's SimplicialLDLT as a LinearSolver ("eigen-ldlt"): for comparison with
// CHOLMOD and for small problems.
#include "linalg/linear_solver.hpp"
#include "linalg/solver_method.hpp"

#include <Eigen/SparseCholesky>

#include <cstdint>

namespace hofem {

class EigenLdltSolver final : public LinearSolver {
 public:
  std::string_view name() const override { return method_name(SolverMethod::EigenLdlt); }
  void analyze(const SparseMatrix& A) override {
    ldlt_.analyzePattern(A);
    ++analyses_;
    pattern_ = pattern_fingerprint(A);
  }
  bool factorize(const SparseMatrix& A) override {
    if (analyses_ == 0 || pattern_fingerprint(A) != pattern_) analyze(A);
    ldlt_.factorize(A);
    ++factorizations_;
    if (ldlt_.info() != Eigen::Success) return false;
    // LDL^T succeeds on indefinite matrices; report them as not positive definite
    // like Cholesky does, so Newton treats both solvers alike.
    return (ldlt_.vectorD().array() > 0.0).all();
  }
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override { x = ldlt_.solve(b); }

 private:
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Upper> ldlt_;
  std::uint64_t pattern_ = 0;  // pattern_fingerprint of the analysed matrix
};

}  // namespace hofem
