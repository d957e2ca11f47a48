#pragma once
// Corotated linear elasticity (thesis eq. 2.11–2.12) with the polar decomposition
// F = R S, R a rotation (det R = +1), S symmetric:
//   psi = mu ||F - R||_F^2 + lambda/2 tr(S - I)^2,
//   P   = 2 mu (F - R) + lambda tr(R^T F - I) R.
// Note on eq. 2.11: the thesis writes the volume term as lambda/2 tr(S - I), which
// is linear in S and whose derivative lambda/2 R does not give eq. 2.12's
// lambda tr(R^T F - I) R (it would not even vanish at F = I). The squared trace
// is the energy whose gradient is eq. 2.12 (d tr(S) = tr(R^T dF) because
// tr(dR^T F) = tr(S W) = 0 for W = R^T dR skew and S symmetric), so that is what
// is implemented.
//
// Inverted F (det F < 0): S cannot be positive definite with det R = +1. We use
// the rotation-variant polar decomposition: the SVD F = U diag(s) V^T with U and V
// both proper rotations, which puts the sign of det F on the smallest singular
// value, then R = U V^T, S = V diag(s) V^T.
// This R maximises tr(R^T F) over rotations, so the model keeps pushing an
// inverted element back. R is discontinuous where two signed singular values sum to
// zero (inverted F with |s_2| = |s_3|); there P jumps and dP/dF does not exist.
//
// Tangent: from F = R S, R^T dF = W S + dS with W = R^T dR skew. The skew part
// gives W S + S W = R^T dF - dF^T R, and for W = [w]x one has
// W S + S W = [(tr(S) I - S) w]x, hence
//   w = (tr(S) I - S)^{-1} axial(R^T dF - dF^T R),  dR = R [w]x,
// and dP = 2 mu (dF - dR) + lambda tr(R^T dF) R + lambda tr(S - I) dR.
// (tr(S) I - S) has eigenvalues s_i + s_j (i != j); it is inverted through the SVD
// with each denominator floored at 1e-10 max(|s_1|, 1) so the tangent stays finite
// at the degenerate states named above and at F of rank <= 1 (where it is
// meaningless anyway). The verification suite checks the factor by finite differences.
#include "material/material.hpp"

namespace hofem {

/// F = R S with det R = +1 (see corotated.hpp). S = V diag(sigma) V^T; sigma is
/// sorted by decreasing magnitude and only sigma[2] can be negative (iff det F < 0).
struct PolarDecomposition {
  Mat3 R;
  Mat3 S;
  Mat3 V;
  Eigen::Vector3d sigma;
};

/// Rotation-variant polar decomposition via Eigen's 3x3 Jacobi SVD (fixed size, no heap).
PolarDecomposition polar_decomposition(const Mat3& F);

class Corotated final : public Material {
 public:
  explicit Corotated(LameParameters lame) : Material(lame) {}
  double evaluate(const Mat3& F, Mat3* P, Mat9* dPdF) const override;
  bool needs_polar_decomposition() const override { return true; }
};

}  // namespace hofem
