#pragma once
#include "report.hpp"

#include "material/material.hpp"

#include <vector>

namespace hofem::verification {

/// Length scale of F for finite differences: its smallest singular value and, for
/// det F < 0, also the smallest |s_i + s_j| of the signed singular values (where
/// the rotation-variant polar decomposition, hence corotated's P, jumps). A step
/// h = c * fd_length_scale(F) keeps F +- h e_b on the same smooth branch.
double fd_length_scale(const Mat3& F);

/// max_b |P_b - (psi(F + h e_b) - psi(F - h e_b)) / 2h| over the 9 entries of vec(F),
/// relative to max(max |P|, mu + |lambda|).
double stress_fd_error(const Material& material, const Mat3& F, double h);

/// max |dPdF(:, b) - (P(F + h e_b) - P(F - h e_b)) / 2h| relative to
/// max(max |dPdF|, mu + |lambda|). `tangent` defaults to the material's own.
double tangent_fd_error(const Material& material, const Mat3& F, double h);
double tangent_fd_error(const Material& material, const Mat3& F, double h, const Mat9& tangent);

/// max |A - A^T| / max |A| for A = dP/dF(F).
double tangent_asymmetry(const Material& material, const Mat3& F);

/// Deterministic samples of F (fixed seed): Q1 diag(s) Q2 with random rotations.
/// regular: s_i in [0.5, 1.6], det F in [0.2, 3]; near_inverted: det F in
/// [0.005, 0.02]; inverted: one stretch negated, det F in [-3, -0.2], the two
/// smallest |s_i| at least 0.1 apart.
struct DeformationSamples {
  std::vector<Mat3> regular, near_inverted, inverted;
};
DeformationSamples deformation_samples(int regular = 20, int near_inverted = 5, int inverted = 10);

/// Every material check: Lamé conversion against hand-computed values; for each of
/// the five materials, P against central differences of psi and dP/dF against
/// central differences of P (regular, near-inverted and, where defined, inverted
/// F), major symmetry of dP/dF, rotation invariance (LinearElastic: documented
/// non-invariance), zero stress and the linear-elastic tangent at F = I, the
/// Neo-Hookean domain (J <= 0) and Stable Neo-Hookean's lack of one; project_psd.
void add_material_checks(Report& report);

}  // namespace hofem::verification
