#pragma once
// Small-strain (linear) elasticity, written as a function of F so it plugs into
// the same element code as the hyperelastic models:
//   eps = sym(F - I),  psi = mu eps:eps + lambda/2 tr(eps)^2,
//   P = 2 mu eps + lambda tr(eps) I,
//   dP_ij/dF_kl = mu (d_ik d_jl + d_il d_jk) + lambda d_ij d_kl   (constant).
// Not rotation invariant: a rigid rotation Q gives eps = sym(Q - I) != 0, so the
// model is only meaningful for small rotations (the verification suite checks that
// psi(QF) != psi(F) as a documented property).
#include "material/material.hpp"

namespace hofem {

class LinearElastic final : public Material {
 public:
  explicit LinearElastic(LameParameters lame);
  double evaluate(const Mat3& F, Mat3* P, Mat9* dPdF) const override;
  /// mu (d_ik d_jl + d_il d_jk) + lambda d_ij d_kl is PSD for mu > 0 and
  /// 3 lambda + 2 mu > 0, which from_young_poisson guarantees (E > 0, -1 < nu < 0.5).
  bool constant_tangent() const override { return true; }
  /// The constant tangent (the elasticity tensor in the flattening of material.hpp).
  const Mat9& tangent() const { return tangent_; }

 private:
  Mat9 tangent_;
};

}  // namespace hofem
