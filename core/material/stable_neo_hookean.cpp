#include "material/stable_neo_hookean.hpp"

#include "material/tensor_ops.hpp"

#include <fmt/format.h>

#include <cmath>

namespace hofem {

StableNeoHookean::StableNeoHookean(LameParameters lame)
    : Material(lame), mu_(4.0 / 3.0 * lame.mu), lambda_(lame.lambda + 5.0 / 6.0 * lame.mu) {
  if (!(lambda_ > 0.0) || !std::isfinite(lambda_) || !std::isfinite(mu_))
    throw std::invalid_argument(fmt::format(
        "stable-neohookean: needs lambda + 5/6 mu > 0 (positive bulk response), got mu = {}, lambda = {}", lame.mu,
        lame.lambda));
  alpha_ = 1.0 + 0.75 * mu_ / lambda_;
}

double StableNeoHookean::evaluate(const Mat3& F, Mat3* P, Mat9* dPdF) const {
  const double Ic = F.squaredNorm();
  const Mat3 C = material_detail::cofactor(F);  // dJ/dF
  const double J = F.col(0).dot(C.col(0));
  const double q = 1.0 / (Ic + 1.0);
  if (P) *P = mu_ * (1.0 - q) * F + lambda_ * (J - alpha_) * C;
  if (dPdF) {
    const auto f = material_detail::vec(F);
    const auto c = material_detail::vec(C);
    Mat9& H = *dPdF;
    H = (2.0 * mu_ * q * q) * f * f.transpose() + lambda_ * c * c.transpose();
    H.diagonal().array() += mu_ * (1.0 - q);
    material_detail::add_determinant_hessian(H, F, lambda_ * (J - alpha_));
  }
  const double dJ = J - alpha_;
  return 0.5 * mu_ * (Ic - 3.0) + 0.5 * lambda_ * dJ * dJ - 0.5 * mu_ * std::log1p(Ic);
}

}  // namespace hofem
