#pragma once
// Conditioning of finite-cell systems (Longva et al. 2020 §5, Fig. 5), group "embedded.fig5".
//
// A 4x4x4 grid of tetrahedra (Tet4 or Tet10) on [0, 4/3]^3 holds the embedded box
// [0, 1 + eps/3]^3: the last layer of cells in each direction is cut to a width
// eps of the cell, so the smallest cut cell has volume fraction eps^3. For each
// eps the backward-Euler matrix A = M + dt^2 K(u) (Stable Neo-Hookean, u(X) =
// (X, X, -X), dt = 1/60, u = 0 on X = 0) is built with and without the §5.3
// quadrature stabilisation (1e-6, no cell dropped), and the condition number of
// S A is measured for S = identity, Jacobi and the Additive-Schwarz preconditioner
// of §5.2 (blocks on the cut cells with volume fraction < 0.5).
//
// The unprojected Hessian is indefinite at this deformation, so A is too and
// kappa = max|lambda| / min|lambda|. S A's spectrum is that of L^T A L, S = L L^T,
// from dense matrices (eigenvalues only); a Schwarz S that is not numerically SPD
// (no stabilisation, eps <= 3e-3 on Tet10) is a breakdown, kappa +inf.
//
// Rows: every kappa as a measurement (the curve of Fig. 5; scripts/plots/plot_fcm.py);
// checks that
//  - the smallest volume fraction is eps^3,
//  - Additive Schwarz with stabilisation stays bounded as eps -> 0 (max over the
//    sweep within 10x of its value at the first eps where every cut cell is a block),
//  - without stabilisation Tet10's kappa (identity and Jacobi) grows at least like 1/eps,
//  - Tet4 with Jacobi alone stays bounded without stabilisation (Longva et al.'s remark).
#include <string>

#include "report.hpp"

namespace hofem::verification {

/// level "ci": Tet4 over the whole eps sweep, Tet10 at eps = 1, 0.2, 0.01 with only
/// the spectra the checks read (~15 s on two cores); "full": both orders, every
/// spectrum, eps = 1 ... 1e-3 (~2.5 min, 60 dense 1944 x 1944 eigen-solves).
void add_fcm_conditioning_checks(Report& report, const std::string& level);

}  // namespace hofem::verification
