#include "linalg/cholmod_solver.hpp"

#include "linalg/blas_threads.hpp"

#include <fmt/format.h>

#include <chrono>
#include <stdexcept>

namespace hofem {

CholmodSolver::CholmodSolver(bool serial_solves) : serial_solves_(serial_solves) {
  cholmod_l_start(&common_);
  // Failures are reported to the caller (factorize() returns false); CHOLMOD's
  // own printing of "not positive definite" warnings would only be noise.
  common_.print = 0;
}

CholmodSolver::~CholmodSolver() {
  if (factor_) cholmod_l_free_factor(&factor_, &common_);
  if (solve_factor_) cholmod_l_free_factor(&solve_factor_, &common_);
  for (cholmod_dense** d : {&X_, &Y_, &E_})
    if (*d) cholmod_l_free_dense(d, &common_);
  cholmod_l_finish(&common_);
}

cholmod_sparse CholmodSolver::view(const SparseMatrix& A) const {
  if (!A.isCompressed()) throw std::invalid_argument("CholmodSolver: matrix must be compressed");
  cholmod_sparse s{};
  s.nrow = static_cast<size_t>(A.rows());
  s.ncol = static_cast<size_t>(A.cols());
  s.nzmax = static_cast<size_t>(A.nonZeros());
  s.p = const_cast<std::int64_t*>(A.outerIndexPtr());
  s.i = const_cast<std::int64_t*>(A.innerIndexPtr());
  s.x = const_cast<double*>(A.valuePtr());
  s.stype = 1;  // symmetric, stored in full: CHOLMOD reads the upper triangle
  s.itype = CHOLMOD_LONG;
  s.xtype = CHOLMOD_REAL;
  s.dtype = CHOLMOD_DOUBLE;
  s.sorted = 1;
  s.packed = 1;
  return s;
}

void CholmodSolver::analyze(const SparseMatrix& A) {
  if (factor_) cholmod_l_free_factor(&factor_, &common_);
  cholmod_sparse s = view(A);
  factor_ = cholmod_l_analyze(&s, &common_);
  if (!factor_) throw std::runtime_error(fmt::format("CHOLMOD analyze failed (status {})", common_.status));
  pattern_ = pattern_fingerprint(A);
  factor_flops_ = common_.fl;    // the analysis' count for one numeric factorisation
  solve_flops_ = 4.0 * common_.lnz;  // forward and back substitution: 2 flops per entry each
  ++analyses_;
}

bool CholmodSolver::factorize(const SparseMatrix& A) {
  if (!factor_ || pattern_fingerprint(A) != pattern_) analyze(A);
  cholmod_sparse s = view(A);
  use_blas_threads_for(factor_flops_);
  const auto t0 = std::chrono::steady_clock::now();
  cholmod_l_factorize(&s, factor_, &common_);
  setup_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ++factorizations_;
  if (common_.status == CHOLMOD_NOT_POSDEF) return false;
  if (common_.status < 0) throw std::runtime_error(fmt::format("CHOLMOD factorize failed (status {})", common_.status));
  // For small or very sparse matrices CHOLMOD chooses a simplicial LDL^T, which
  // completes on indefinite matrices (negative entries in D) without reporting
  // CHOLMOD_NOT_POSDEF; Newton then took an ascent direction on an inverted
  // Stable Neo-Hookean state. Positive definite means every D(j,j) > 0; in the
  // simplicial LDL^T storage D(j,j) is the first entry of column j.
  if (!factor_->is_super && !factor_->is_ll) {
    const auto* Lp = static_cast<const SuiteSparse_long*>(factor_->p);
    const auto* Lx = static_cast<const double*>(factor_->x);
    for (size_t j = 0; j < factor_->n; ++j)
      if (!(Lx[Lp[j]] > 0.0)) return false;
  }
  if (serial_solves_) {
    if (solve_factor_) cholmod_l_free_factor(&solve_factor_, &common_);
    solve_factor_ = cholmod_l_copy_factor(factor_, &common_);
    // Simplicial, numeric LL^T, packed, monotonic: the solves walk columns, no BLAS.
    if (!solve_factor_ || !cholmod_l_change_factor(CHOLMOD_REAL, 1, 0, 1, 1, solve_factor_, &common_))
      throw std::runtime_error(fmt::format("CHOLMOD change_factor failed (status {})", common_.status));
  }
  return true;
}

void CholmodSolver::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  if (!factor_) throw std::logic_error("CholmodSolver::solve before factorize");
  cholmod_dense B{};
  B.nrow = static_cast<size_t>(b.size());
  B.ncol = 1;
  B.nzmax = B.nrow;
  B.d = B.nrow;
  B.x = const_cast<double*>(b.data());
  B.xtype = CHOLMOD_REAL;
  B.dtype = CHOLMOD_DOUBLE;
  // solve2 keeps X and its workspaces between calls (allocated on the first
  // solve, or again when the size changes): no allocation per solve, which
  // matters where the solve runs inside every preconditioner application (the
  // coarse level of pmg).
  use_blas_threads_for(solve_flops_);
  if (!cholmod_l_solve2(CHOLMOD_A, serial_solves_ ? solve_factor_ : factor_, &B, nullptr, &X_, nullptr, &Y_, &E_, &common_))
    throw std::runtime_error(fmt::format("CHOLMOD solve failed (status {})", common_.status));
  x = Eigen::Map<const Eigen::VectorXd>(static_cast<const double*>(X_->x), b.size());
}

}  // namespace hofem
