#include "material/corotated.hpp"

#include "material/tensor_ops.hpp"

#include <Eigen/LU>  // determinant
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>

namespace hofem {

using material_detail::cross_matrix;
using material_detail::Vec3;

PolarDecomposition polar_decomposition(const Mat3& F) {
  // Eigen's two-sided Jacobi SVD works on F itself (no F^T F), so small singular
  // values stay accurate and F = R S holds to ~eps ||F|| even for nearly singular
  // F. Square input: no QR preconditioner needed. Fixed size: no heap allocation.
  const Eigen::JacobiSVD<Mat3, Eigen::NoQRPreconditioner> svd(F, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Mat3 U = svd.matrixU();
  PolarDecomposition p;
  p.V = svd.matrixV();
  p.sigma = svd.singularValues();  // non-negative, decreasing
  // Make U and V proper rotations; each reflection removed negates the smallest
  // singular value (and the matching column), so it ends up negative exactly
  // when det F < 0.
  if (U.determinant() < 0.0) {
    U.col(2) = -U.col(2);
    p.sigma[2] = -p.sigma[2];
  }
  if (p.V.determinant() < 0.0) {
    p.V.col(2) = -p.V.col(2);
    p.sigma[2] = -p.sigma[2];
  }
  p.R = U * p.V.transpose();
  p.S = p.V * p.sigma.asDiagonal() * p.V.transpose();
  return p;
}

namespace {

Mat9 tangent_from(const PolarDecomposition& pd, const LameParameters& lame) {
  const Vec3& s = pd.sigma;
  const double trS = s.sum();
  // (tr(S) I - S)^{-1} = V diag(1 / (trS - s_i)) V^T, denominators floored (see header).
  const double floor = 1e-10 * std::max(std::fabs(s[0]), 1.0);
  Vec3 inv;
  for (int i = 0; i < 3; ++i) inv[i] = 1.0 / std::max(trS - s[i], floor);
  const Mat3 Ginv = pd.V * inv.asDiagonal() * pd.V.transpose();
  const Mat3& R = pd.R;
  const double c = lame.lambda * (trS - 3.0) - 2.0 * lame.mu;  // coefficient of dR = R [w]x
  Mat9 H;
  for (int l = 0; l < 3; ++l)
    for (int k = 0; k < 3; ++k) {
      // dF = e_k e_l^T: R^T dF - dF^T R = r e_l^T - e_l r^T with r = R^T e_k, whose axial vector is e_l x r.
      const Vec3 r = R.row(k).transpose();
      const Vec3 w = Ginv * Vec3::Unit(l).cross(r);
      Mat3 dP = (c * R) * cross_matrix(w) + (lame.lambda * R(k, l)) * R;
      dP(k, l) += 2.0 * lame.mu;
      H.col(k + 3 * l) = material_detail::vec(dP);
    }
  return H;
}

}  // namespace

double Corotated::evaluate(const Mat3& F, Mat3* P, Mat9* dPdF) const {
  const PolarDecomposition pd = polar_decomposition(F);
  const double tr = pd.sigma.sum() - 3.0;
  if (P) *P = 2.0 * lame_.mu * (F - pd.R) + lame_.lambda * tr * pd.R;
  if (dPdF) *dPdF = tangent_from(pd, lame_);
  // ||F - R||^2 = ||U (diag(s) - I) V^T||^2 = sum (s_i - 1)^2: exactly zero at rotations.
  return lame_.mu * (pd.sigma.array() - 1.0).square().sum() + 0.5 * lame_.lambda * tr * tr;
}

}  // namespace hofem
