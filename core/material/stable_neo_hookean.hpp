#pragma once
// Stable Neo-Hookean (Smith, de Goes, Kim 2018, "Stable Neo-Hookean Flesh
// Simulation", ACM TOG 37(2), article 12), J = det F, I_C = ||F||_F^2:
//   psi = mu/2 (I_C - 3) + lambda/2 (J - alpha)^2 - mu/2 log(I_C + 1),
//   P   = mu (1 - 1/(I_C + 1)) F + lambda (J - alpha) cof(F),   cof(F) = dJ/dF,
//   dP/dF = mu (1 - 1/(I_C + 1)) I_9 + 2 mu/(I_C + 1)^2 vec(F) vec(F)^T
//           + lambda vec(cof F) vec(cof F)^T + lambda (J - alpha) d^2J/dF^2.
// Rest stability: at F = I (I_C = 3, J = 1, cof = I), P = (3 mu/4 - lambda (alpha - 1)) I,
// which vanishes iff alpha = 1 + 3 mu / (4 lambda).
// psi, P and dP/dF are polynomials in F plus log(I_C + 1) with I_C + 1 >= 1, so they
// are defined and smooth for every F, inverted (J <= 0) included: no exceptions.
// (psi(I) = lambda/2 (1 - alpha)^2 - mu/2 log 4 is not zero; the paper's constant is kept.)
//
// Lamé mapping. Linearising P at F = I (d cof = tr(dF) I - dF^T there) gives
//   dP = 3mu/4 (dF + dF^T) + (lambda - 5mu/8) tr(dF) I,
// i.e. small-strain Lamé parameters mu_L = 3mu/4 and lambda_L = lambda - 5mu/8. As in
// the paper, the model's (mu, lambda) are chosen so that it matches linear
// elasticity with the given (mu_L, lambda_L) at rest:
//   mu = 4/3 mu_L,  lambda = lambda_L + 5/6 mu_L   (so alpha = 1 + mu_L / lambda).
// Then E and nu keep their meaning for small strains, and all five hofem materials
// share the same tangent at F = I (checked by the verification suite). lame() still
// returns the given (mu_L, lambda_L); model_mu() / model_lambda() the mapped ones.
// lambda = lambda_L + 5/6 mu_L > 0 holds for every (E, nu) with E > 0, -1 < nu < 0.5
// (it is E/(1+nu) (nu/(1-2nu) + 5/12) >= E/(12(1+nu))); other inputs are rejected.
#include "material/material.hpp"

namespace hofem {

class StableNeoHookean final : public Material {
 public:
  /// Throws std::invalid_argument unless lambda_L + 5/6 mu_L > 0 (finite).
  explicit StableNeoHookean(LameParameters lame);
  double evaluate(const Mat3& F, Mat3* P, Mat9* dPdF) const override;
  double model_mu() const { return mu_; }
  double model_lambda() const { return lambda_; }
  double alpha() const { return alpha_; }

 private:
  double mu_, lambda_, alpha_;
};

}  // namespace hofem
