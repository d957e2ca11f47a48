#pragma once
#include "report.hpp"

namespace hofem::verification {

/// Element energy / gradient / Hessian against central finite differences, and
/// Hessian symmetry, for Tet orders 1-3, Hex8 and Hex20 and every material, on a
/// randomly distorted (curved, for order >= 2) element under a random deformation.
/// Also the consistent mass matrix's total mass.
void add_element_checks(Report& report);

/// Patch tests: linear elasticity on distorted meshes reproduces every polynomial
/// displacement of the element's degree (given the matching body force).
void add_patch_checks(Report& report);

}  // namespace hofem::verification
