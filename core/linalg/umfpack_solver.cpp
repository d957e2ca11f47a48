#include "linalg/umfpack_solver.hpp"

#include "linalg/blas_threads.hpp"

#include <fmt/format.h>
#include <umfpack.h>

#include <stdexcept>

namespace hofem {

namespace {
// Eigen's 64-bit indices are the SuiteSparse_long the dl interface expects.
static_assert(sizeof(SuiteSparse_long) == sizeof(std::int64_t));
const SuiteSparse_long* idx(const std::int64_t* p) { return reinterpret_cast<const SuiteSparse_long*>(p); }
}  // namespace

UmfpackSolver::~UmfpackSolver() {
  free_numeric();
  if (symbolic_) umfpack_dl_free_symbolic(&symbolic_);
}

void UmfpackSolver::free_numeric() {
  if (numeric_) umfpack_dl_free_numeric(&numeric_);
}

void UmfpackSolver::analyze(const SparseMatrix& A) {
  if (!A.isCompressed()) throw std::invalid_argument("UmfpackSolver: matrix must be compressed");
  free_numeric();
  if (symbolic_) umfpack_dl_free_symbolic(&symbolic_);
  double info[UMFPACK_INFO];
  const int status = umfpack_dl_symbolic(A.rows(), A.cols(), idx(A.outerIndexPtr()), idx(A.innerIndexPtr()), A.valuePtr(),
                                         &symbolic_, nullptr, info);
  if (status != UMFPACK_OK) throw std::runtime_error(fmt::format("UMFPACK symbolic analysis failed (status {})", status));
  pattern_ = pattern_fingerprint(A);
  // The symbolic analysis' upper bounds for the numeric factorisation and the
  // factors' entries (2 flops per entry for each of the two triangular solves).
  factor_flops_ = info[UMFPACK_FLOPS_ESTIMATE];
  solve_flops_ = 4.0 * (info[UMFPACK_LNZ_ESTIMATE] + info[UMFPACK_UNZ_ESTIMATE]);
  ++analyses_;
}

bool UmfpackSolver::factorize(const SparseMatrix& A) {
  if (!symbolic_ || pattern_fingerprint(A) != pattern_) analyze(A);
  free_numeric();
  use_blas_threads_for(factor_flops_);
  const int status =
      umfpack_dl_numeric(idx(A.outerIndexPtr()), idx(A.innerIndexPtr()), A.valuePtr(), symbolic_, &numeric_, nullptr, nullptr);
  ++factorizations_;
  A_ = &A;
  if (status == UMFPACK_WARNING_singular_matrix) return false;
  if (status != UMFPACK_OK) throw std::runtime_error(fmt::format("UMFPACK numeric factorisation failed (status {})", status));
  return true;
}

void UmfpackSolver::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  if (!numeric_ || !A_) throw std::logic_error("UmfpackSolver::solve before factorize");
  x.resize(b.size());
  use_blas_threads_for(solve_flops_);
  const int status = umfpack_dl_solve(UMFPACK_A, idx(A_->outerIndexPtr()), idx(A_->innerIndexPtr()), A_->valuePtr(), x.data(),
                                      b.data(), numeric_, nullptr, nullptr);
  if (status != UMFPACK_OK) throw std::runtime_error(fmt::format("UMFPACK solve failed (status {})", status));
}

}  // namespace hofem
