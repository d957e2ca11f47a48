// IC(0) (linalg/incomplete_cholesky.hpp) on the 2-D 5-point Laplacian, whose
// complete Cholesky factor has fill: the incomplete factor keeps exactly A's
// lower pattern, differs from the complete factor, and reproduces A on A's
// pattern (the defining property of IC(0): (L L^T)(i, j) = A(i, j) there).
#include "linalg/incomplete_cholesky.hpp"
#include "linalg/preconditioner.hpp"
#include "solver/solver_factory.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace hofem {
namespace {

// m x m grid, Dirichlet boundary: 4 on the diagonal, -1 to each grid neighbour.
SparseMatrix laplacian_2d(int m) {
  std::vector<Eigen::Triplet<double, std::int64_t>> t;
  auto id = [m](int i, int j) { return static_cast<std::int64_t>(i) * m + j; };
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) {
      t.emplace_back(id(i, j), id(i, j), 4.0);
      if (i > 0) t.emplace_back(id(i, j), id(i - 1, j), -1.0);
      if (i + 1 < m) t.emplace_back(id(i, j), id(i + 1, j), -1.0);
      if (j > 0) t.emplace_back(id(i, j), id(i, j - 1), -1.0);
      if (j + 1 < m) t.emplace_back(id(i, j), id(i, j + 1), -1.0);
    }
  SparseMatrix A(m * m, m * m);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  return A;
}

TEST(IncompleteCholesky0, ZeroFillFactorOfThe5PointLaplacian) {
  const SparseMatrix A = laplacian_2d(6);
  IncompleteCholesky0 ic;
  ASSERT_TRUE(ic.compute(A));
  EXPECT_EQ(ic.shift(), 0.0);  // an M-matrix: IC(0) exists without a shift
  const SparseMatrix& L = ic.lower();
  const SparseMatrix tril = A.triangularView<Eigen::Lower>();
  // The pattern of L is the pattern of tril(A), entry for entry.
  ASSERT_EQ(L.nonZeros(), tril.nonZeros());
  for (Eigen::Index k = 0; k <= L.cols(); ++k) ASSERT_EQ(L.outerIndexPtr()[k], SparseMatrix(tril).outerIndexPtr()[k]);
  for (Eigen::Index q = 0; q < L.nonZeros(); ++q) ASSERT_EQ(L.innerIndexPtr()[q], SparseMatrix(tril).innerIndexPtr()[q]);
  // The complete factor (natural ordering) has fill, so L is not it.
  Eigen::SimplicialLLT<SparseMatrix, Eigen::Lower, Eigen::NaturalOrdering<std::int64_t>> full(A);
  ASSERT_EQ(full.info(), Eigen::Success);
  const SparseMatrix Lfull = full.matrixL();
  EXPECT_GT(Lfull.nonZeros(), L.nonZeros());
  EXPECT_GT((Eigen::MatrixXd(Lfull) - Eigen::MatrixXd(L)).cwiseAbs().maxCoeff(), 1e-3);
  // L L^T equals A on A's pattern to rounding: each entry is a sum of at most
  // ~5 products of entries <= 2 in size, so 1e-14 absolute is ~50 eps.
  const Eigen::MatrixXd LLt = Eigen::MatrixXd(L) * Eigen::MatrixXd(L).transpose();
  for (Eigen::Index c = 0; c < A.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(A, c); it; ++it)
      EXPECT_NEAR(LLt(it.row(), it.col()), it.value(), 1e-14) << it.row() << ", " << it.col();
  // And off A's pattern it differs (the dropped fill): somewhere by > 1e-3.
  double off = 0.0;
  for (Eigen::Index i = 0; i < A.rows(); ++i)
    for (Eigen::Index j = 0; j < A.cols(); ++j)
      if (A.coeff(i, j) == 0.0) off = std::max(off, std::fabs(LLt(i, j)));
  EXPECT_GT(off, 1e-3);
  // The preconditioner applies (L L^T)^{-1}: L L^T z = r.
  auto pc = make_preconditioner("ic0");
  ASSERT_TRUE(pc->setup(A));
  const Eigen::VectorXd r = Eigen::VectorXd::LinSpaced(A.rows(), -1.0, 2.0);
  Eigen::VectorXd z;
  pc->apply(r, z);
  EXPECT_LE((LLt * z - r).norm(), 1e-12 * r.norm());
}

// An SPD matrix whose IC(0) breaks down without a shift: with the fill entry
// (3, 2) dropped, the last pivot is 3 - 1.9^2/3 x 2 - ... = -1.02 (computed by
// hand from the recurrence). The documented restart with a diagonal shift
// alpha diag(A) must then succeed, with positive pivots, and reproduce
// A + alpha diag(A) on A's pattern.
TEST(IncompleteCholesky0, ShiftsOnBreakdown) {
  Eigen::MatrixXd D(4, 4);
  D << 3, -1.9, -1.9, 0,  //
      -1.9, 3, 0, -1.9,   //
      -1.9, 0, 3, 1.9,    //
      0, -1.9, 1.9, 3;
  ASSERT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(D).eigenvalues().minCoeff(), 0.0);  // SPD
  const SparseMatrix A = D.sparseView();
  IncompleteCholesky0 ic;
  ASSERT_TRUE(ic.compute(A));
  EXPECT_GT(ic.shift(), 0.0);
  const Eigen::MatrixXd L(ic.lower());
  for (Eigen::Index k = 0; k < 4; ++k) EXPECT_GT(L(k, k), 0.0);
  const Eigen::MatrixXd LLt = L * L.transpose();
  for (Eigen::Index i = 0; i < 4; ++i)
    for (Eigen::Index j = 0; j < 4; ++j)
      if (D(i, j) != 0.0) {
        EXPECT_NEAR(LLt(i, j), D(i, j) * (i == j ? 1.0 + ic.shift() : 1.0), 1e-13) << i << ", " << j;
      }
}

}  // namespace
}  // namespace hofem
