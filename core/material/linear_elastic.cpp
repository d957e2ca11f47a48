#include "material/linear_elastic.hpp"

namespace hofem {

LinearElastic::LinearElastic(LameParameters lame) : Material(lame) {
  // Row a = i + 3j, column b = k + 3l.
  tangent_.setZero();
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      tangent_(i + 3 * j, i + 3 * j) += lame.mu;  // mu d_ik d_jl
      tangent_(i + 3 * j, j + 3 * i) += lame.mu;  // mu d_il d_jk
    }
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) tangent_(4 * i, 4 * k) += lame.lambda;  // lambda d_ij d_kl
}

double LinearElastic::evaluate(const Mat3& F, Mat3* P, Mat9* dPdF) const {
  const Mat3 eps = 0.5 * (F + F.transpose()) - Mat3::Identity();
  const double tr = eps.trace();
  if (P) *P = 2.0 * lame_.mu * eps + lame_.lambda * tr * Mat3::Identity();
  if (dPdF) *dPdF = tangent_;
  return lame_.mu * eps.squaredNorm() + 0.5 * lame_.lambda * tr * tr;
}

}  // namespace hofem
