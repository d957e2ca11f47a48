#pragma once
// Compressible Neo-Hookean (thesis eq. 2.13–2.14), J = det F, I1 = ||F||_F^2:
//   psi = mu/2 (I1 - 3) - mu log J + lambda/2 (log J)^2,
//   P   = mu (F - F^{-T}) + lambda log(J) F^{-T}.
// Tangent, with G = F^{-T} and d(F^{-T}) = -G dF^T G, d log J = G : dF:
//   dP_ij/dF_kl = mu d_ik d_jl + lambda G_ij G_kl + (mu - lambda log J) G_il G_kj.
// Defined only for J > 0: energy() returns +infinity for J <= 0 (so a line search
// backs off), stress() and stress_derivative() throw MaterialDomainError naming the
// material and det F.
#include "material/material.hpp"

namespace hofem {

class NeoHookean final : public Material {
 public:
  explicit NeoHookean(LameParameters lame) : Material(lame) {}
  bool defined_at(const Mat3& F) const override;
  double evaluate(const Mat3& F, Mat3* P, Mat9* dPdF) const override;
};

}  // namespace hofem
