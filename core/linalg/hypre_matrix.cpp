#include "linalg/hypre_matrix.hpp"

#include <HYPRE_utilities.h>
#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace hofem {

void hypre_check(HYPRE_Int code, const char* what) {
  if (code == 0) return;
  char description[256] = {};
  HYPRE_DescribeError(code, description);
  // hypre keeps a global error flag that later calls would report again.
  HYPRE_ClearAllErrors();
  throw std::runtime_error(fmt::format("{} failed (hypre error {}: {})", what, code, description));
}

std::string hypre_matrix_problem(const SparseMatrix& A) {
  if (A.rows() != A.cols()) return fmt::format("matrix is {} x {}, not square", A.rows(), A.cols());
  constexpr auto kMaxIndex = std::numeric_limits<HYPRE_Int>::max();
  if (A.rows() > kMaxIndex || A.nonZeros() > kMaxIndex)
    return fmt::format("{} rows, {} nonzeros exceed hypre's 32-bit indices (this hypre build has no --enable-bigint)",
                       A.rows(), A.nonZeros());
  std::vector<bool> has_positive_diagonal(A.rows(), false);
  for (Eigen::Index c = 0; c < A.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(A, c); it; ++it) {
      if (!std::isfinite(it.value()))
        return fmt::format("entry ({}, {}) is {}", it.row(), it.col(), it.value());
      if (it.row() == c && it.value() > 0.0) has_positive_diagonal[c] = true;
    }
  for (Eigen::Index i = 0; i < A.rows(); ++i)
    if (!has_positive_diagonal[i]) return fmt::format("diagonal entry {} is {} (needs > 0)", i, A.coeff(i, i));
  return {};
}

// --- HypreMatrix ----------------------------------------------------------------

HypreMatrix::~HypreMatrix() { destroy(); }

void HypreMatrix::destroy() {
  if (ij_) HYPRE_IJMatrixDestroy(ij_);  // also frees the ParCSR object it built
  ij_ = nullptr;
  parcsr_ = nullptr;
}

void HypreMatrix::assign(const SparseMatrix& A_in) {
  // The value array is handed to hypre as it is: it must be contiguous.
  SparseMatrix compressed;
  const SparseMatrix* A = &A_in;
  if (!A_in.isCompressed()) {
    compressed = A_in;
    compressed.makeCompressed();
    A = &compressed;
  }
  destroy();
  // A is symmetric and stored in full, so its compressed columns are its rows.
  const HYPRE_Int n = static_cast<HYPRE_Int>(A->rows());
  std::vector<HYPRE_Int> row_sizes(n), no_offd(n, 0);
  std::vector<HYPRE_BigInt> rows(n), cols(A->innerIndexPtr(), A->innerIndexPtr() + A->nonZeros());
  std::iota(rows.begin(), rows.end(), HYPRE_BigInt{0});
  for (HYPRE_Int c = 0; c < n; ++c)
    row_sizes[c] = static_cast<HYPRE_Int>(A->outerIndexPtr()[c + 1] - A->outerIndexPtr()[c]);
  // Rows and columns [0, n): everything lands in hypre's "diag" block.
  hypre_check(HYPRE_IJMatrixCreate(MPI_COMM_SELF, 0, n - 1, 0, n - 1, &ij_), "HYPRE_IJMatrixCreate");
  hypre_check(HYPRE_IJMatrixSetObjectType(ij_, HYPRE_PARCSR), "HYPRE_IJMatrixSetObjectType");
  // Exact row sizes: hypre allocates once instead of growing rows
  // (HYPRE_IJ_mv.h: "should always be utilized if possible").
  if (n > 0)
    hypre_check(HYPRE_IJMatrixSetDiagOffdSizes(ij_, row_sizes.data(), no_offd.data()), "HYPRE_IJMatrixSetDiagOffdSizes");
  hypre_check(HYPRE_IJMatrixInitialize(ij_), "HYPRE_IJMatrixInitialize");
  if (n > 0)
    hypre_check(HYPRE_IJMatrixSetValues(ij_, n, row_sizes.data(), rows.data(), cols.data(), A->valuePtr()),
                "HYPRE_IJMatrixSetValues");
  hypre_check(HYPRE_IJMatrixAssemble(ij_), "HYPRE_IJMatrixAssemble");
  void* object = nullptr;
  hypre_check(HYPRE_IJMatrixGetObject(ij_, &object), "HYPRE_IJMatrixGetObject");
  parcsr_ = static_cast<HYPRE_ParCSRMatrix>(object);
}

// --- HypreVector ----------------------------------------------------------------

HypreVector::~HypreVector() { destroy(); }

void HypreVector::destroy() {
  if (ij_) HYPRE_IJVectorDestroy(ij_);
  ij_ = nullptr;
  par_ = nullptr;
  ids_.clear();
}

void HypreVector::conform(HYPRE_ParCSRMatrix A) {
  MPI_Comm comm = MPI_COMM_NULL;
  HYPRE_BigInt row_first = 0, row_last = -1, col_first = 0, col_last = -1;
  hypre_check(HYPRE_ParCSRMatrixGetComm(A, &comm), "HYPRE_ParCSRMatrixGetComm");
  hypre_check(HYPRE_ParCSRMatrixGetLocalRange(A, &row_first, &row_last, &col_first, &col_last),
              "HYPRE_ParCSRMatrixGetLocalRange");
  const auto local = static_cast<size_t>(row_last - row_first + 1);
  if (ij_ && comm == comm_ && ids_.size() == local && (local == 0 || ids_.front() == row_first)) return;
  destroy();
  comm_ = comm;
  hypre_check(HYPRE_IJVectorCreate(comm, row_first, row_last, &ij_), "HYPRE_IJVectorCreate");
  hypre_check(HYPRE_IJVectorSetObjectType(ij_, HYPRE_PARCSR), "HYPRE_IJVectorSetObjectType");
  hypre_check(HYPRE_IJVectorInitialize(ij_), "HYPRE_IJVectorInitialize");
  hypre_check(HYPRE_IJVectorAssemble(ij_), "HYPRE_IJVectorAssemble");
  void* object = nullptr;
  hypre_check(HYPRE_IJVectorGetObject(ij_, &object), "HYPRE_IJVectorGetObject");
  par_ = static_cast<HYPRE_ParVector>(object);
  ids_.resize(local);
  std::iota(ids_.begin(), ids_.end(), row_first);
  set_zero();
}

// Set/GetValues write and read the local part in place; values owned here need
// no further Assemble (that only ships values set for other ranks).
void HypreVector::set(const Eigen::Ref<const Eigen::VectorXd>& v) {
  if (v.size() != static_cast<Eigen::Index>(ids_.size()))
    throw std::invalid_argument(fmt::format("hypre vector has {} local rows, got {}", ids_.size(), v.size()));
  if (!ids_.empty()) hypre_check(HYPRE_IJVectorSetValues(ij_, local_size(), ids_.data(), v.data()), "HYPRE_IJVectorSetValues");
}

void HypreVector::get(Eigen::VectorXd& v) const {
  v.resize(static_cast<Eigen::Index>(ids_.size()));
  if (!ids_.empty()) hypre_check(HYPRE_IJVectorGetValues(ij_, local_size(), ids_.data(), v.data()), "HYPRE_IJVectorGetValues");
}

void HypreVector::set_zero() { hypre_check(HYPRE_ParVectorSetConstantValues(par_, 0.0), "HYPRE_ParVectorSetConstantValues"); }

double hypre_dot(const HypreVector& x, const HypreVector& y) {
  HYPRE_Real d = 0.0;
  hypre_check(HYPRE_ParVectorInnerProd(x.par(), y.par(), &d), "HYPRE_ParVectorInnerProd");
  return d;
}

}  // namespace hofem
