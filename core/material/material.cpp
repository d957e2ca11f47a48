// Lamé conversion and the PSD projection of a tangent (the factory: material_registry.cpp).
#include "material/material.hpp"


#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <fmt/format.h>

#include <cmath>

namespace hofem {

// Isotropic linear elasticity: mu = E / (2 (1 + nu)), lambda = E nu / ((1 + nu)(1 - 2 nu)).
// nu -> 0.5 sends lambda to infinity and nu -> -1 sends mu to infinity, so both ends
// are open; E must be positive and finite. (!(x > a)) also rejects NaN.
LameParameters LameParameters::from_young_poisson(double young, double poisson) {
  if (!(young > 0.0) || !std::isfinite(young))
    throw std::invalid_argument(fmt::format("Young's modulus must be positive and finite, got {}", young));
  if (!(poisson > -1.0 && poisson < 0.5))
    throw std::invalid_argument(fmt::format("Poisson's ratio must lie in (-1, 0.5), got {}", poisson));
  LameParameters p;
  p.mu = young / (2.0 * (1.0 + poisson));
  p.lambda = young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
  return p;
}

long long polar_decompositions(const Material& material, long long assemblies, long long elements, long long points) {
  return material.needs_polar_decomposition() ? assemblies * elements * points : 0;
}

// The input is symmetrised first (the eigensolver would otherwise read only the
// lower triangle). A matrix that is already positive (semi-)definite is returned as
// given, bit for bit: first a Cholesky attempt (~10x cheaper than the eigensolver)
// catches the common case of a numerically positive definite tangent, then the
// eigenvalues catch PSD matrices with zero eigenvalues. Otherwise the result is
// V max(D, 0) V^T, the nearest PSD matrix in the Frobenius norm.
Mat9 project_psd(const Mat9& A) {
  const Mat9 sym = 0.5 * (A + A.transpose());
  if (Eigen::LLT<Mat9>(sym).info() == Eigen::Success) return A;
  Eigen::SelfAdjointEigenSolver<Mat9> eig(sym);
  const auto& d = eig.eigenvalues();
  if (d.minCoeff() >= 0.0) return A;
  const Eigen::Matrix<double, 9, 1> clamped = d.cwiseMax(0.0);
  const Mat9& V = eig.eigenvectors();
  // Coefficient-based product: for 9x9, Eigen would otherwise dispatch to its
  // blocked GEMM (with OpenMP thread queries), far slower at this size.
  return (V * clamped.asDiagonal()).lazyProduct(V.transpose());
}

}  // namespace hofem
