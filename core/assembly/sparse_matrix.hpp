#pragma once
// The sparse matrix type at the boundary between assembly and linear algebra:
// compressed columns with 64-bit indices (CHOLMOD's long interface takes the
// arrays as they are; an MPI path can replace it with hypre's ParCSR later
// without touching elements or materials). Symmetric matrices are stored in full.
#include <Eigen/SparseCore>

#include <cstdint>

namespace hofem {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, std::int64_t>;

/// 64-bit FNV-1a hash of a compressed matrix's size and pattern (not its values).
/// Solvers and preconditioners that reuse symbolic work (orderings, Galerkin
/// products) compare it to notice a new pattern without keeping a copy; O(nnz)
/// integer work, negligible beside any factorisation or set-up.
inline std::uint64_t pattern_fingerprint(const SparseMatrix& A) {
  std::uint64_t h = 1469598103934665603ull;
  auto mix = [&h](std::int64_t v) { h = (h ^ static_cast<std::uint64_t>(v)) * 1099511628211ull; };
  mix(A.rows());
  mix(A.cols());
  mix(A.nonZeros());
  for (Eigen::Index j = 0; j <= A.outerSize(); ++j) mix(A.outerIndexPtr()[j]);
  for (Eigen::Index q = 0; q < A.nonZeros(); ++q) mix(A.innerIndexPtr()[q]);
  return h;
}

}  // namespace hofem
