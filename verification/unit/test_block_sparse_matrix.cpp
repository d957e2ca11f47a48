// BlockSparseMatrix (linalg/block_sparse_matrix.hpp) against Eigen's compressed
// columns on an assembled stiffness matrix: the same products, the same matrix
// back, values refreshed in place.
#include "assembly/assembler.hpp"
#include "material/material.hpp"
#include "mesh/box_mesh.hpp"
#include "linalg/block_sparse_matrix.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace hofem {
namespace {

// A clamped linear-elastic P2 cube (E = 1, nu = 0.3), 2 cells per side: 3x3 node
// blocks, rows of different lengths, constrained nodes removed.
SparseMatrix stiffness(double scale = 1.0) {
  const Mesh m = box_mesh(unit_cube(2), CellType::Tetrahedron, 2);
  const DofMap dofs(m.num_nodes(), m.node_set("xmin"));
  const Assembler a(m, dofs);
  const auto mat = make_material("linear", LameParameters::from_young_poisson(scale, 0.3));
  Eigen::VectorXd g;
  SparseMatrix K = a.new_matrix();
  a.hessian(*mat, Eigen::Map<const Eigen::VectorXd>(m.nodes.data(), 3 * m.num_nodes()), g, K, false);
  return K;
}

Eigen::VectorXd test_vector(Eigen::Index n) {
  Eigen::VectorXd x(n);
  for (Eigen::Index i = 0; i < n; ++i) x[i] = std::sin(0.7 * static_cast<double>(i) + 0.3);
  return x;
}

// |A| |x| bounds the rounding of any summation order of A x.
Eigen::VectorXd abs_product(const SparseMatrix& A, const Eigen::VectorXd& x) {
  return SparseMatrix(A.cwiseAbs()) * x.cwiseAbs();
}

// Double blocks: the same sums as Eigen in another order, so each entry agrees to
// a few ulp of |A| |x| (4 eps allows the ~27-term sums' reordering); float
// blocks: each value rounded once to 2^-24 relative, so 2^-24 |A| |x| plus the
// double rounding.
TEST(BlockSparseMatrix, ProductsMatchTheAssembledMatrix) {
  const SparseMatrix K = stiffness();
  const Eigen::VectorXd x = test_vector(K.rows()), b = test_vector(K.rows()).reverse();
  const Eigen::VectorXd ref = K * x, bound = abs_product(K, x);
  const BlockSparseMatrix<double> Bd(K);
  const BlockSparseMatrix<float> Bf(Bd);
  ASSERT_EQ(Bd.rows(), K.rows());
  Eigen::VectorXd y, r;
  Bd.multiply(x, y);
  EXPECT_TRUE(((y - ref).cwiseAbs().array() <= 4e-16 * 27 * bound.array()).all());
  Bd.residual(b, x, r);
  EXPECT_TRUE(((r - (b - ref)).cwiseAbs().array() <= 4e-16 * 27 * bound.array() + 4e-16 * b.cwiseAbs().array()).all());
  Bf.multiply(x, y);
  EXPECT_TRUE(((y - ref).cwiseAbs().array() <= (std::ldexp(1.0, -24) + 4e-16 * 27) * bound.array()).all());
  // The same matrix back, and its diagonal blocks. A block row is read from K's
  // columns (K is symmetric), and the assembled K is symmetric only to rounding
  // (the (i, j) and (j, i) sums run in different orders; observed <= 4e-17 on
  // entries ~0.1): 1e-15 relative.
  EXPECT_EQ((Bd.to_sparse() - K).norm(), 0.0);
  for (Eigen::Index i = 0; i < Bd.block_rows(); ++i) {
    const Eigen::Matrix3d Kii = K.block(3 * i, 3 * i, 3, 3);
    EXPECT_LE((Bd.diagonal_block(i) - Kii).norm(), 1e-15 * Kii.norm()) << "block row " << i;
  }
}

// A matrix whose nodes are not whole in its pattern (two symmetric entries of one
// 3x3 block dropped: the columns of that node differ in length) takes the
// general construction (merged block columns, missing entries stored as zeros):
// the same products and the same matrix back as the assembled one minus the
// dropped pair.
TEST(BlockSparseMatrix, BuildsFromAMatrixNotStructuredByNodes) {
  SparseMatrix K = stiffness();
  const Eigen::Index a = 0, b = 4;  // node 0's x row, node 1's y column
  ASSERT_NE(K.coeff(a, b), 0.0);
  K.prune([&](Eigen::Index r, Eigen::Index c, double) { return !((r == a && c == b) || (r == b && c == a)); });
  K.makeCompressed();
  ASSERT_EQ(K.coeff(a, b), 0.0);
  const BlockSparseMatrix<double> B(K);
  const Eigen::VectorXd x = test_vector(K.rows());
  Eigen::VectorXd y;
  B.multiply(x, y);
  EXPECT_TRUE(((y - K * x).cwiseAbs().array() <= 4e-16 * 27 * abs_product(K, x).array()).all());
  EXPECT_EQ((B.to_sparse() - K).norm(), 0.0);
}

// New values on the same pattern: set_values (from the assembled matrix) and
// assign (from another block matrix, any precision) keep the structure and give
// exactly what building anew gives.
TEST(BlockSparseMatrix, RefreshesValuesInPlace) {
  const SparseMatrix K1 = stiffness(1.0), K2 = stiffness(3.7);
  BlockSparseMatrix<double> Bd(K1);
  BlockSparseMatrix<float> Bf(Bd);
  Bd.set_values(K2);
  EXPECT_EQ((Bd.to_sparse() - K2).norm(), 0.0);
  const float* before = Bf.block_values(0);
  Bf.assign(Bd);
  EXPECT_EQ(Bf.block_values(0), before);  // no new storage
  const BlockSparseMatrix<float> fresh(Bd);
  for (std::int64_t k = 0; k < Bf.blocks(); ++k)
    for (int v = 0; v < 9; ++v) ASSERT_EQ(Bf.block_values(k)[v], fresh.block_values(k)[v]) << "block " << k;
  // Another structure: assign takes it whole.
  BlockSparseMatrix<float> other(BlockSparseMatrix<double>(stiffness().topLeftCorner(30, 30)));
  other.assign(Bd);
  EXPECT_EQ(other.blocks(), Bd.blocks());
  EXPECT_EQ((BlockSparseMatrix<double>(other).to_sparse() - SparseMatrix(fresh.to_sparse())).norm(), 0.0);
}

}  // namespace
}  // namespace hofem
