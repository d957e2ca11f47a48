// LAPACK's symmetric eigenvalues (verification/suite/dense_eigenvalues.hpp) on
// matrices whose spectrum is known by construction: Q diag(lambda) Q^T with Q
// orthogonal.
#include "dense_eigenvalues.hpp"

#include <Eigen/QR>
#include <gtest/gtest.h>

#include <algorithm>

namespace hofem::verification {
namespace {

TEST(DenseEigenvalues, RecoversAPrescribedIndefiniteSpectrum) {
  const int n = 300;
  Eigen::VectorXd lambda = Eigen::VectorXd::LinSpaced(n, -5.0, 1000.0);
  lambda[7] = 1e-6;  // a small one among large: the absolute error bound still holds
  const Eigen::MatrixXd Q = Eigen::HouseholderQR<Eigen::MatrixXd>(Eigen::MatrixXd::Random(n, n)).householderQ();
  const Eigen::MatrixXd A = Q * lambda.asDiagonal() * Q.transpose();
  const auto w = symmetric_eigenvalues(A);
  ASSERT_TRUE(w.has_value());
  std::sort(lambda.begin(), lambda.end());
  // Backward stable: each eigenvalue within c n eps ||A||_2 (||A||_2 = 1000);
  // 1e-9 = ~15 x n eps ||A|| leaves room for the rounding of Q diag Q^T itself.
  EXPECT_LE((*w - lambda).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_TRUE(std::is_sorted(w->begin(), w->end()));
}

TEST(DenseEigenvalues, EmptyAndNonSquare) {
  EXPECT_EQ(symmetric_eigenvalues(Eigen::MatrixXd(0, 0))->size(), 0);
  EXPECT_THROW(symmetric_eigenvalues(Eigen::MatrixXd::Zero(2, 3)), std::invalid_argument);
}

}  // namespace
}  // namespace hofem::verification
