#pragma once
// The finite-cell set-up's fast paths against the reference (group
// "embedded.setup"): the Hex20 tube of the twisting-cylinder scene (r 0.5 to 1,
// height 3, 1 x 16 x 8 cells of 6 tets) in a 2 x 2 x 3 Hex20 box grid, its rules
// built twice - once as the seed built them (SVD and a fresh pivoted QR per
// active-set solve, clipped mass rules) and once as scenes now do (CholeskyQR2
// and an updated QR, moment-fitted mass rules; quadrature_simplification.hpp) -
// then stabilised and folded as a scene does. The rows compare what the
// assembler sees: the stiffness rules' points and the stiffness and mass
// matrices.
#include "report.hpp"

namespace hofem::verification {

void add_fcm_setup_checks(Report& report);

}  // namespace hofem::verification
