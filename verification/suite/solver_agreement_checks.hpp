#pragma once
#include "report.hpp"

namespace hofem::verification {

/// The same discretisation solved iteratively and directly gives the same
/// answer: per element family (Tet4, Tet10, Tet20 FEM; Hex8, Hex20 FCM), the
/// twisting cylinder at nu = 0.48 run with the iterative path "auto" takes
/// above its direct limits (set-up reuse included) and with CHOLMOD; the
/// surface RMS distance between the two at every recorded frame is held to
/// 1e-3 of the study's threshold. Group "agreement.iterative_direct".
void add_solver_agreement_checks(Report& report);

}  // namespace hofem::verification
