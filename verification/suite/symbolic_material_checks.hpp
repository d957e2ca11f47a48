#pragma once
#include "report.hpp"

namespace hofem::verification {

/// core/material against the laws sympy derives from the strain energies as
/// their sources write them (symbolic_material.hpp): for each of the five
/// materials and each kind of deformation (regular, near-inverted and, where
/// the material is defined, inverted F), the largest relative difference of psi,
/// P and dP/dF; the generator's list of materials against material_names().
/// Group "material.symbolic".
void add_symbolic_material_checks(Report& report);

}  // namespace hofem::verification
