#include "material/st_venant_kirchhoff.hpp"

namespace hofem {

namespace {

// dP_ij/dF_kl = d_ik S_lj + mu [(F F^T)_ik d_jl + F_il F_kj] + lambda F_ij F_kl,
// row i + 3j, column k + 3l; written entry by entry (faster than 3x3 block
// expressions at this size).
Mat9 tangent(const Mat3& F, const Mat3& S, const LameParameters& p) {
  const Mat3 muB = p.mu * F * F.transpose();
  const Mat3 lamF = p.lambda * F, muF = p.mu * F;
  Mat9 H;
  for (int l = 0; l < 3; ++l)
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
          double h = lamF(i, j) * F(k, l) + muF(i, l) * F(k, j);
          if (i == k) h += S(l, j);
          if (j == l) h += muB(i, k);
          H(i + 3 * j, k + 3 * l) = h;
        }
  return H;
}

}  // namespace

double StVenantKirchhoff::evaluate(const Mat3& F, Mat3* P, Mat9* dPdF) const {
  const Mat3 E = 0.5 * (F.transpose() * F - Mat3::Identity());
  const double tr = E.trace();
  if (P || dPdF) {
    // Second Piola–Kirchhoff stress S = 2 mu E + lambda tr(E) I; P = F S.
    const Mat3 S = 2.0 * lame_.mu * E + lame_.lambda * tr * Mat3::Identity();
    if (P) *P = F * S;
    if (dPdF) *dPdF = tangent(F, S, lame_);
  }
  return lame_.mu * E.squaredNorm() + 0.5 * lame_.lambda * tr * tr;
}

}  // namespace hofem
