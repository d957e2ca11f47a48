#pragma once
#include "report.hpp"

#include <string>

namespace hofem::verification {

/// Longva et al. 2020 Fig. 10: static L2 convergence of FCM Hex8 / Hex20 on a half
/// ball (manufactured solution) against staircase FEM on the same grids.
/// level "ci": grids 1/4, 1/8; "full": 1/4 to 1/32. Group "embedded.fig10".
void add_fcm_convergence_checks(Report& report, const std::string& level);

}  // namespace hofem::verification
