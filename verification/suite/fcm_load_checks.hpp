#pragma once
#include "report.hpp"

namespace hofem::verification {

/// The finite cell method's load functional on cut cells: body-force and
/// surface-traction loads of the Fig. 10 half ball on Hex8 / Hex20 grids
/// (h = 1/6, 1/10: other cuts than the Fig. 10 grids) against the exact work of polynomial fields, and against the
/// divergence theorem for fields with kinks at the cell faces. Group "embedded.loads".
void add_fcm_load_checks(Report& report);

}  // namespace hofem::verification
