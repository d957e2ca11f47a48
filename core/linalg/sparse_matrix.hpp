#pragma once
// The sparse matrix type at the boundary between assembly and linear algebra:
// compressed columns with 64-bit indices (CHOLMOD's long interface takes the
// arrays as they are; an MPI path can replace it with hypre's ParCSR later
// without touching elements or materials). Symmetric matrices are stored in full.
#include <Eigen/SparseCore>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

namespace hofem {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, std::int64_t>;

/// A scalar matrix over the mesh nodes (node i, node j), 32-bit indices: the
/// consistent mass of an isotropic density is this times the 3x3 identity, so
/// it is stored once per node pair instead of three times over the DOFs.
using NodalMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

/// An allocator whose resize() leaves new elements uninitialised (default-init
/// instead of value-init): value arrays of ~100 MB are written in parallel right
/// after allocation, so a serial zero fill first would double their cost.
template <class T>
struct UninitializedAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = UninitializedAllocator<U>;
  };
  UninitializedAllocator() = default;
  template <class U>
  UninitializedAllocator(const UninitializedAllocator<U>&) noexcept {}
  template <class U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

/// 64-bit hash of a compressed matrix's size and pattern (not its values).
/// Solvers and preconditioners that reuse symbolic work (orderings, Galerkin
/// products) compare it to notice a new pattern without keeping a copy. FNV-1a
/// over fixed chunks of 2^16 indices (four interleaved chains each), the chunks' hashes combined in order: the
/// value does not depend on the thread count, and the chunks run in parallel (one
/// FNV chain is a 4-cycle multiply per index: ~20 ms serially for the 17 M
/// indices of P3 n = 12, which two solvers hash at every set-up).
inline std::uint64_t pattern_fingerprint(const SparseMatrix& A) {
  constexpr std::uint64_t kOffset = 1469598103934665603ull, kPrime = 1099511628211ull;
  auto mix = [](std::uint64_t& h, std::int64_t v) { h = (h ^ static_cast<std::uint64_t>(v)) * kPrime; };
  std::uint64_t h = kOffset;
  mix(h, A.rows());
  mix(h, A.cols());
  mix(h, A.nonZeros());
  for (Eigen::Index j = 0; j <= A.outerSize(); ++j) mix(h, A.outerIndexPtr()[j]);
  constexpr std::int64_t kChunk = std::int64_t{1} << 16;
  const std::int64_t nnz = A.nonZeros(), chunks = (nnz + kChunk - 1) / kChunk;
  std::vector<std::uint64_t> chunk_hash(static_cast<size_t>(chunks), kOffset);
  const std::int64_t* inner = A.innerIndexPtr();
#pragma omp parallel for schedule(static) if (chunks > 4)
  for (std::int64_t c = 0; c < chunks; ++c) {
    std::uint64_t lane[4] = {kOffset, kOffset + 1, kOffset + 2, kOffset + 3};  // 4 independent chains
    const std::int64_t end = std::min(nnz, (c + 1) * kChunk);
    for (std::int64_t q = c * kChunk; q < end; ++q) mix(lane[q & 3], inner[q]);
    for (std::uint64_t l : lane) mix(chunk_hash[c], static_cast<std::int64_t>(l));
  }
  std::uint64_t combined = kOffset;
  for (std::uint64_t hc : chunk_hash) mix(combined, static_cast<std::int64_t>(hc));
  mix(h, static_cast<std::int64_t>(combined));
  return h;
}

}  // namespace hofem
