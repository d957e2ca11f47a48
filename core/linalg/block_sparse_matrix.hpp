#pragma once
// A symmetric matrix in 3x3 blocks (block compressed rows, 32-bit block column
// indices), for the products that dominate iterative solves. Elasticity couples
// the three displacement components of every pair of neighbouring nodes, and the
// free numbering keeps a node's components consecutive (DofMap), so a 3x3 block
// is the natural unit: one index per 9 values instead of one 64-bit index per
// value. Bytes per stored value: Eigen's compressed columns 16; this in double
// 8.4, in float 4.4. A product is memory-bound (one pass over the values), so
// those ratios are its speed-ups (measured in benchmarks/bench_bandwidth.cpp).
//
// Float values serve preconditioners (multigrid levels, smoothers), whose
// operators need not be exact; vectors and sums stay in double.
//
// Built from the assembled SparseMatrix (symmetric, stored in full, size a
// multiple of 3); set_values() refreshes the values for a matrix of the same
// pattern (every Newton iteration) without rebuilding the structure. Products
// run in parallel over block rows (OpenMP) above a size where that pays.
#include "linalg/sparse_matrix.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <utility>
#include <vector>

namespace hofem {

template <class T>
class BlockSparseMatrix {
 public:
  BlockSparseMatrix() = default;
  /// Structure and values of A. Throws std::invalid_argument if A is not square,
  /// not compressed, or its size is not a multiple of 3.
  explicit BlockSparseMatrix(const SparseMatrix& A);
  /// A given block structure (block row i: column[row_start[i] .. row_start[i+1]-1],
  /// ascending) with zero values, to be filled through block_values().
  BlockSparseMatrix(std::vector<std::int32_t> row_start, std::vector<std::int32_t> column);
  /// The same matrix in another precision.
  template <class U>
  explicit BlockSparseMatrix(const BlockSparseMatrix<U>& other);
  /// This becomes `other` in this precision: values only (converted on every
  /// thread) when the block structure is the same (compared: 4 bytes per block
  /// against the 36 or 72 converted), else structure and values. A Newton
  /// iteration's new values keep the structure, so nothing is allocated.
  template <class U>
  void assign(const BlockSparseMatrix<U>& other);
  /// Values of A, whose pattern must be the one this was built from (checked by
  /// size and nonzero count; a different pattern throws std::invalid_argument).
  void set_values(const SparseMatrix& A);

  Eigen::Index rows() const { return 3 * block_rows(); }
  Eigen::Index block_rows() const { return static_cast<Eigen::Index>(row_start_.size()) - 1; }
  std::int64_t blocks() const { return static_cast<std::int64_t>(column_.size()); }
  /// Bytes one product reads from the matrix (values and indices).
  std::int64_t bytes() const;

  /// y = A x.
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  /// r = b - A x.
  void residual(const Eigen::VectorXd& b, const Eigen::VectorXd& x, Eigen::VectorXd& r) const;
  /// (A x) restricted to block row i (3 values), for smoothers that fuse work per row.
  Eigen::Vector3d row_product(Eigen::Index i, const double* x) const;
  const std::vector<std::int32_t>& row_start() const { return row_start_; }
  const std::vector<std::int32_t>& column() const { return column_; }
  /// The 9 values of block k (column-major within the block: entry (a, b) at 3 b + a).
  T* block_values(std::int64_t k) { return value_.data() + 9 * k; }
  const T* block_values(std::int64_t k) const { return value_.data() + 9 * k; }
  /// The same matrix as compressed columns (for direct solvers and AMG on coarse levels).
  SparseMatrix to_sparse() const;
  /// The diagonal block of block row i.
  Eigen::Matrix3d diagonal_block(Eigen::Index i) const;
  /// Whether products run in parallel (enough work to pay for a parallel region).
  bool parallel() const { return parallel_; }
  /// pattern_fingerprint() of the matrix this was built from, when its builder
  /// recorded it (0 otherwise): a consumer of the block copy need not hash again.
  std::uint64_t source_fingerprint() const { return source_fingerprint_; }
  void set_source_fingerprint(std::uint64_t f) { source_fingerprint_ = f; }

 private:
  std::vector<std::int32_t> row_start_{0};  ///< block row i: blocks row_start_[i] .. row_start_[i+1]-1
  std::vector<std::int32_t> column_;        ///< block column of each block, ascending in a row
  std::vector<std::int32_t> diagonal_;      ///< position of each row's diagonal block (-1: none)
  /// 9 per block, column-major within the block (a column is 3 consecutive
  /// values, so a 4-wide load takes it whole), plus padding for the last load.
  std::vector<T, UninitializedAllocator<T>> value_;
  std::int64_t source_nonzeros_ = 0;        ///< nonzeros of the matrix it was built from
  std::uint64_t source_fingerprint_ = 0;
  bool parallel_ = false;

  template <class U>
  friend class BlockSparseMatrix;
  void finish_structure();  // diagonal_, parallel_ from row_start_ and column_
  void build_general(const SparseMatrix& A);  // structure by merging columns, then set_values()
};

template <class T>
template <class U>
BlockSparseMatrix<T>::BlockSparseMatrix(const BlockSparseMatrix<U>& other)
    : row_start_(other.row_start_), column_(other.column_), diagonal_(other.diagonal_),
      source_nonzeros_(other.source_nonzeros_), parallel_(other.parallel_) {
  value_.resize(other.value_.size());  // uninitialised: converted on every thread, by assign()
  assign(other);
}

template <class T>
template <class U>
void BlockSparseMatrix<T>::assign(const BlockSparseMatrix<U>& other) {
  if (row_start_ != other.row_start_ || column_ != other.column_ || value_.size() != other.value_.size()) {
    *this = BlockSparseMatrix<T>(other);
    return;
  }
  const std::int64_t n = static_cast<std::int64_t>(value_.size());
  T* out = value_.data();
  const U* in = other.value_.data();
#pragma omp parallel for schedule(static) if (parallel_)
  for (std::int64_t k = 0; k < n; ++k) out[k] = static_cast<T>(in[k]);
}

extern template class BlockSparseMatrix<float>;
extern template class BlockSparseMatrix<double>;

}  // namespace hofem
