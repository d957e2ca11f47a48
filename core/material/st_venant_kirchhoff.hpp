#pragma once
// St. Venant–Kirchhoff (thesis eq. 2.9–2.10):
//   E = (F^T F - I) / 2,  psi = mu ||E||_F^2 + lambda/2 tr(E)^2,
//   P = F S with S = 2 mu E + lambda tr(E) I  (= 2 mu F E + lambda tr(E) F, eq. 2.10).
// Tangent: dP = dF S + F dS, dS = 2 mu dE + lambda tr(dE) I, dE = sym(F^T dF);
// for dF = e_k e_l^T this gives
//   dP_ij/dF_kl = d_ik S_lj + mu [(F F^T)_ik d_jl + F_il F_kj] + lambda F_ij F_kl.
// Defined for every F (also inverted); it softens under strong compression and is
// not a barrier against inversion (thesis §2.2.1).
#include "material/material.hpp"

namespace hofem {

class StVenantKirchhoff final : public Material {
 public:
  explicit StVenantKirchhoff(LameParameters lame) : Material(lame) {}
  double evaluate(const Mat3& F, Mat3* P, Mat9* dPdF) const override;
};

}  // namespace hofem
