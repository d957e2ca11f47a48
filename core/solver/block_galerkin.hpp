#pragma once
// The Galerkin coarse operator of a p-multigrid level, A_c = (P ⊗ I3)^T A (P ⊗ I3)
// (thesis Algorithm 3's A_{l-1}), on 3x3 block matrices: P holds one weight per
// (fine node, coarse node) pair and acts on each displacement component alike, so
// each coarse block is a weighted sum of fine blocks,
//   A_c(I, J) = sum_k sum_l P(k, I) P(l, J) A(k, l).
// For the spaces of a p-hierarchy the coarse space lies inside the fine one, so
// this is exactly the coarse discretisation of the fine operator (for linear
// elasticity with exact quadrature, the matrix assembly on the coarse order would
// give), for any matrix (a Newton Hessian included) without re-assembling.
//
// galerkin_structure() finds A_c's block pattern once per fine pattern;
// galerkin_values() writes the values, coarse block rows in parallel, each thread
// with its own position map.
#include "linalg/block_sparse_matrix.hpp"
#include "solver/p_hierarchy.hpp"

namespace hofem {

/// A_c's block structure from A's and the transfer's; returns A_c with zero values.
BlockSparseMatrix<double> galerkin_structure(const BlockSparseMatrix<double>& A, const NodeTransfer& t);
/// Values of A_c (which must come from galerkin_structure() with this A's pattern and t).
void galerkin_values(const BlockSparseMatrix<double>& A, const NodeTransfer& t, BlockSparseMatrix<double>& Ac);

}  // namespace hofem
