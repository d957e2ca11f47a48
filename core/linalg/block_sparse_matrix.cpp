#include "linalg/block_sparse_matrix.hpp"

#include <fmt/format.h>
#if defined(__AVX2__) && defined(__FMA__)
#include <immintrin.h>
#endif

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace hofem {

namespace {

// Below this many blocks (~2e5 values, ~0.1 ms of products) a product runs
// serially: a parallel region's barrier would cost about as much as it saves.
constexpr std::int64_t kParallelBlocks = 20000;
// The last block's third column is read with a 4-wide load.
constexpr size_t kPadding = 4;

// The block columns of block row i of a symmetric A (its columns 3i..3i+2, which
// are its rows), merged and without repeats, passed to emit in ascending order.
template <class Emit>
void block_columns(const SparseMatrix& A, Eigen::Index i, Emit&& emit) {
  const std::int64_t* outer = A.outerIndexPtr();
  const std::int64_t* inner = A.innerIndexPtr();
  std::int64_t q[3], end[3];
  for (int c = 0; c < 3; ++c) q[c] = outer[3 * i + c], end[c] = outer[3 * i + c + 1];
  std::int64_t last = -1;
  while (true) {
    std::int64_t next = std::numeric_limits<std::int64_t>::max();
    for (int c = 0; c < 3; ++c)
      if (q[c] < end[c]) next = std::min(next, inner[q[c]] / 3);
    if (next == std::numeric_limits<std::int64_t>::max()) break;
    if (next != last) emit(next), last = next;
    for (int c = 0; c < 3; ++c)
      while (q[c] < end[c] && inner[q[c]] / 3 == next) ++q[c];
  }
}

// The number of blocks of block row i when its three columns hold the same rows
// in whole aligned triples (3m, 3m + 1, 3m + 2): every matrix assembled over
// nodes with all or none of their components free (SparsityPattern). Then block
// k of the row is column inner[outer[3i] + 3k] / 3, and no merge is needed.
// -1 otherwise.
std::int64_t node_structured_blocks(const SparseMatrix& A, Eigen::Index i) {
  const std::int64_t* outer = A.outerIndexPtr();
  const std::int64_t* inner = A.innerIndexPtr();
  const std::int64_t length = outer[3 * i + 1] - outer[3 * i];
  if (length % 3 != 0 || outer[3 * i + 2] - outer[3 * i + 1] != length || outer[3 * i + 3] - outer[3 * i + 2] != length)
    return -1;
  for (int c = 0; c < 3; ++c) {
    const std::int64_t* r = inner + outer[3 * i + c];
    for (std::int64_t q = 0; q < length; q += 3)
      if (r[q] % 3 != 0 || r[q + 1] != r[q] + 1 || r[q + 2] != r[q] + 2 || r[q] != inner[outer[3 * i] + q]) return -1;
  }
  return length / 3;
}

}  // namespace

// Structure and values in one pass over A when every block row is node-structured
// (every matrix SparsityPattern makes): the columns' lengths say the block counts,
// and each row's indices are read once, checked and turned into block columns
// while its values are copied. Any other matrix (or a row that fails the check)
// takes the general path: merged block columns, then set_values().
template <class T>
BlockSparseMatrix<T>::BlockSparseMatrix(const SparseMatrix& A) {
  if (A.rows() != A.cols() || !A.isCompressed() || A.rows() % 3 != 0)
    throw std::invalid_argument(fmt::format("BlockSparseMatrix: needs a compressed square matrix of size 3k, got {}x{}{}",
                                            A.rows(), A.cols(), A.isCompressed() ? "" : " (not compressed)"));
  const Eigen::Index nb = A.rows() / 3;
  const std::int64_t* outer = A.outerIndexPtr();
  const std::int64_t* inner = A.innerIndexPtr();
  const double* val = A.valuePtr();
  bool lengths_structured = true;
  std::int64_t total = 0;
  for (Eigen::Index i = 0; i < nb && lengths_structured; ++i) {
    const std::int64_t length = outer[3 * i + 1] - outer[3 * i];
    lengths_structured = length % 3 == 0 && outer[3 * i + 2] - outer[3 * i + 1] == length &&
                         outer[3 * i + 3] - outer[3 * i + 2] == length;
    total += length / 3;
  }
  if (!lengths_structured || total > std::numeric_limits<std::int32_t>::max()) {
    build_general(A);
    return;
  }
  row_start_.resize(static_cast<size_t>(nb) + 1);
  row_start_[0] = 0;
  for (Eigen::Index i = 0; i < nb; ++i)
    row_start_[i + 1] = row_start_[i] + static_cast<std::int32_t>((outer[3 * i + 1] - outer[3 * i]) / 3);
  column_.resize(static_cast<size_t>(total));
  diagonal_.assign(static_cast<size_t>(nb), -1);
  value_.resize(9 * column_.size() + kPadding);  // uninitialised: every block is written below
  std::fill(value_.end() - kPadding, value_.end(), T(0));
  parallel_ = blocks() >= kParallelBlocks;
  source_nonzeros_ = A.nonZeros();
  bool structured = true;
#pragma omp parallel for schedule(static) reduction(&& : structured) if (parallel_)
  for (Eigen::Index i = 0; i < nb; ++i) {
    const std::int64_t* first = inner + outer[3 * i];
    for (std::int32_t k = row_start_[i], t = 0; k < row_start_[i + 1]; ++k, t += 3) {
      const std::int64_t r = first[t];
      structured = structured && r % 3 == 0;
      column_[k] = static_cast<std::int32_t>(r / 3);
      if (r / 3 == i) diagonal_[i] = k;
      T* v = value_.data() + 9 * static_cast<std::int64_t>(k);
      for (int a = 0; a < 3; ++a) {  // column 3i + a of A is row 3i + a (symmetric): entry (a, c) of the block
        const std::int64_t q = outer[3 * i + a] + t;
        for (int c = 0; c < 3; ++c) {
          structured = structured && inner[q + c] == r + c;
          v[3 * c + a] = static_cast<T>(val[q + c]);
        }
      }
    }
  }
  if (!structured) build_general(A);
}

template <class T>
void BlockSparseMatrix<T>::build_general(const SparseMatrix& A) {
  const Eigen::Index nb = A.rows() / 3;
  std::vector<std::int64_t> count(static_cast<size_t>(nb) + 1, 0);
  const bool parallel = A.nonZeros() >= 9 * kParallelBlocks;
#pragma omp parallel for schedule(static) if (parallel)
  for (Eigen::Index i = 0; i < nb; ++i) {
    std::int64_t k = node_structured_blocks(A, i);
    if (k < 0) {
      k = 0;
      block_columns(A, i, [&](std::int64_t) { ++k; });
    }
    count[i + 1] = k;
  }
  for (Eigen::Index i = 0; i < nb; ++i) count[i + 1] += count[i];
  if (count[nb] > std::numeric_limits<std::int32_t>::max())
    throw std::length_error(fmt::format("BlockSparseMatrix: {} blocks exceed 32-bit indices", count[nb]));
  row_start_.assign(count.begin(), count.end());
  column_.resize(static_cast<size_t>(count[nb]));
  diagonal_.assign(static_cast<size_t>(nb), -1);
#pragma omp parallel for schedule(static) if (parallel)
  for (Eigen::Index i = 0; i < nb; ++i) {
    std::int32_t k = row_start_[i];
    auto emit = [&](std::int64_t j) {
      if (j == i) diagonal_[i] = k;
      column_[k++] = static_cast<std::int32_t>(j);
    };
    if (const std::int64_t blocks = node_structured_blocks(A, i); blocks >= 0) {
      const std::int64_t* first = A.innerIndexPtr() + A.outerIndexPtr()[3 * i];
      for (std::int64_t t = 0; t < blocks; ++t) emit(first[3 * t] / 3);
    } else {
      block_columns(A, i, emit);
    }
  }
  value_.resize(9 * column_.size() + kPadding);  // set_values() writes every block on the thread that reads it
  std::fill(value_.end() - kPadding, value_.end(), T(0));
  parallel_ = blocks() >= kParallelBlocks;
  source_nonzeros_ = A.nonZeros();
  set_values(A);
}

template <class T>
BlockSparseMatrix<T>::BlockSparseMatrix(std::vector<std::int32_t> row_start, std::vector<std::int32_t> column)
    : row_start_(std::move(row_start)), column_(std::move(column)) {
  if (row_start_.empty() || row_start_.front() != 0 || row_start_.back() != static_cast<std::int32_t>(column_.size()))
    throw std::invalid_argument("BlockSparseMatrix: row starts do not match the block columns");
  value_.assign(9 * column_.size() + kPadding, T(0));
  finish_structure();
}

template <class T>
void BlockSparseMatrix<T>::finish_structure() {
  const Eigen::Index nb = block_rows();
  diagonal_.assign(static_cast<size_t>(nb), -1);
  for (Eigen::Index i = 0; i < nb; ++i)
    for (std::int32_t k = row_start_[i]; k < row_start_[i + 1]; ++k)
      if (column_[k] == i) diagonal_[i] = k;
  parallel_ = blocks() >= kParallelBlocks;
  source_nonzeros_ = -1;  // not built from a SparseMatrix: set_values() refuses
}

template <class T>
SparseMatrix BlockSparseMatrix<T>::to_sparse() const {
  // Symmetric: the transpose of block row i is block column i; entries in column
  // 3i + b are, row by row, block (i, j)'s column b as rows 3j..3j+2 of A^T = A.
  const Eigen::Index nb = block_rows();
  SparseMatrix A(rows(), rows());
  A.resizeNonZeros(static_cast<Eigen::Index>(9 * blocks()));
  std::int64_t* outer = A.outerIndexPtr();
  std::int64_t* inner = A.innerIndexPtr();
  double* val = A.valuePtr();
  std::int64_t q = 0;
  outer[0] = 0;
  for (Eigen::Index i = 0; i < nb; ++i)
    for (int b = 0; b < 3; ++b) {
      for (std::int32_t k = row_start_[i]; k < row_start_[i + 1]; ++k) {
        const T* v = value_.data() + 9 * static_cast<std::int64_t>(k);
        for (int a = 0; a < 3; ++a) {
          inner[q] = 3 * static_cast<std::int64_t>(column_[k]) + a;
          val[q++] = v[3 * a + b];  // A(3i + b, 3j + a) = A(3j + a, 3i + b)
        }
      }
      outer[3 * i + b + 1] = q;
    }
  return A;
}

template <class T>
void BlockSparseMatrix<T>::set_values(const SparseMatrix& A) {
  if (A.rows() != rows() || A.cols() != rows() || A.nonZeros() != source_nonzeros_ || !A.isCompressed())
    throw std::invalid_argument("BlockSparseMatrix::set_values: the matrix has another pattern");
  const std::int64_t* outer = A.outerIndexPtr();
  const std::int64_t* inner = A.innerIndexPtr();
  const double* val = A.valuePtr();
  const Eigen::Index nb = block_rows();
#pragma omp parallel for schedule(static) if (parallel_)
  for (Eigen::Index i = 0; i < nb; ++i) {
    std::fill(value_.begin() + 9 * static_cast<std::int64_t>(row_start_[i]),
              value_.begin() + 9 * static_cast<std::int64_t>(row_start_[i + 1]), T(0));
    for (int a = 0; a < 3; ++a) {  // row 3i + a of A is its column (symmetric)
      std::int32_t k = row_start_[i];
      for (std::int64_t q = outer[3 * i + a]; q < outer[3 * i + a + 1]; ++q) {
        const std::int64_t r = inner[q];
        while (column_[k] != r / 3) ++k;  // both ascending
        value_[9 * static_cast<std::int64_t>(k) + 3 * (r % 3) + a] = static_cast<T>(val[q]);  // (a, r % 3)
      }
    }
  }
}

template <class T>
std::int64_t BlockSparseMatrix<T>::bytes() const {
  return static_cast<std::int64_t>((value_.size() - kPadding) * sizeof(T) + column_.size() * sizeof(std::int32_t) +
                                   row_start_.size() * sizeof(std::int32_t));
}

namespace {

#if defined(__AVX2__) && defined(__FMA__)
// Software prefetch of the values kPrefetchValues ahead (4 KB of floats, 8 KB of
// doubles), every cache line of them: a block is 36 bytes in float (one line per
// block covers them all), 72 in double (two lines). The hardware prefetcher alone
// leaves a product latency-bound. Measured on the P3 n = 12 matrix (1.86 M blocks,
// 2 threads, best of 30): float 4.83 -> 1.76 ms, double 7.90 -> 6.86 ms; distances
// 512-4096 values within 10 % of each other, 128 clearly worse.
constexpr std::int64_t kPrefetchValues = 1024;
template <class T>
inline void prefetch_ahead(const T* w) {
  _mm_prefetch(reinterpret_cast<const char*>(w + kPrefetchValues), _MM_HINT_T0);
  if constexpr (sizeof(T) == 8) _mm_prefetch(reinterpret_cast<const char*>(w + kPrefetchValues + 8), _MM_HINT_T0);
}

// One block column (3 values and the next one, ignored) as 4 doubles.
inline __m256d load_column(const double* v) { return _mm256_loadu_pd(v); }
inline __m256d load_column(const float* v) { return _mm256_cvtps_pd(_mm_loadu_ps(v)); }
#endif

}  // namespace

// The product of one block row: per block, c0 x0 + c1 x1 + c2 x2 on 4-wide vectors
// (the three products summed as a tree, so the running sum's dependency chain has
// one addition per block), two running sums for alternate blocks. Without AVX2 the
// same sums in scalar code.
template <class T>
Eigen::Vector3d BlockSparseMatrix<T>::row_product(Eigen::Index i, const double* x) const {
  const std::int32_t begin = row_start_[i], end = row_start_[i + 1];
  const T* v = value_.data() + 9 * static_cast<std::int64_t>(begin);
#if defined(__AVX2__) && defined(__FMA__)
  __m256d even = _mm256_setzero_pd(), odd = _mm256_setzero_pd();
  std::int32_t k = begin;
  auto block = [&](std::int32_t b, const T* w) {
    prefetch_ahead(w);
    const double* xc = x + 3 * static_cast<std::int64_t>(column_[b]);
    const __m256d t = _mm256_fmadd_pd(load_column(w + 6), _mm256_set1_pd(xc[2]),
                                      _mm256_mul_pd(load_column(w), _mm256_set1_pd(xc[0])));
    return _mm256_fmadd_pd(load_column(w + 3), _mm256_set1_pd(xc[1]), t);
  };
  for (; k + 3 < end; k += 4, v += 36) {
    even = _mm256_add_pd(even, _mm256_add_pd(block(k, v), block(k + 2, v + 18)));
    odd = _mm256_add_pd(odd, _mm256_add_pd(block(k + 1, v + 9), block(k + 3, v + 27)));
  }
  for (; k + 1 < end; k += 2, v += 18) {
    even = _mm256_add_pd(even, block(k, v));
    odd = _mm256_add_pd(odd, block(k + 1, v + 9));
  }
  if (k < end) even = _mm256_add_pd(even, block(k, v));
  alignas(32) double out[4];
  _mm256_store_pd(out, _mm256_add_pd(even, odd));
  return {out[0], out[1], out[2]};
#else
  double a0 = 0.0, a1 = 0.0, a2 = 0.0;
  for (std::int32_t k = begin; k < end; ++k, v += 9) {
    const double* xc = x + 3 * static_cast<std::int64_t>(column_[k]);
    a0 += v[0] * xc[0] + v[3] * xc[1] + v[6] * xc[2];
    a1 += v[1] * xc[0] + v[4] * xc[1] + v[7] * xc[2];
    a2 += v[2] * xc[0] + v[5] * xc[1] + v[8] * xc[2];
  }
  return {a0, a1, a2};
#endif
}

template <class T>
void BlockSparseMatrix<T>::multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  const Eigen::Index nb = block_rows();
  if (y.size() != rows()) y.resize(rows());
  const double* xp = x.data();
  double* yp = y.data();
#pragma omp parallel for schedule(static) if (parallel_)
  for (Eigen::Index i = 0; i < nb; ++i) Eigen::Map<Eigen::Vector3d>(yp + 3 * i) = row_product(i, xp);
}

template <class T>
void BlockSparseMatrix<T>::residual(const Eigen::VectorXd& b, const Eigen::VectorXd& x, Eigen::VectorXd& r) const {
  const Eigen::Index nb = block_rows();
  if (r.size() != rows()) r.resize(rows());
  const double* xp = x.data();
  const double* bp = b.data();
  double* rp = r.data();
#pragma omp parallel for schedule(static) if (parallel_)
  for (Eigen::Index i = 0; i < nb; ++i)
    Eigen::Map<Eigen::Vector3d>(rp + 3 * i) = Eigen::Map<const Eigen::Vector3d>(bp + 3 * i) - row_product(i, xp);
}

template <class T>
Eigen::Matrix3d BlockSparseMatrix<T>::diagonal_block(Eigen::Index i) const {
  Eigen::Matrix3d D = Eigen::Matrix3d::Zero();
  if (diagonal_[i] < 0) return D;
  const T* v = value_.data() + 9 * static_cast<std::int64_t>(diagonal_[i]);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) D(a, b) = v[3 * b + a];
  return D;
}

template class BlockSparseMatrix<float>;
template class BlockSparseMatrix<double>;

}  // namespace hofem
