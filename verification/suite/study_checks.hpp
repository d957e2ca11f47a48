#pragma once
#include "report.hpp"

namespace hofem::verification {

/// The scene error measures of core/study against cases whose answer is known:
/// a run against itself (0), a rigidly translated run (d), and a Tet10
/// refinement sequence of a smooth static scene (a hollow torus) against a Tet20
/// reference (the L2 rate p + 1 = 3, asserted >= p + 0.7). Group "study".
void add_study_checks(Report& report);

}  // namespace hofem::verification
