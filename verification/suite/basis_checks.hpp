#pragma once
#include "report.hpp"

#include "basis/reference_basis.hpp"

namespace hofem::verification {

/// The checks of one basis: Kronecker property at the nodes, partition of unity,
/// gradients summing to zero, exact reproduction of its polynomial space (values
/// and gradients), gradients against central finite differences.
void check_basis(Report& report, const ReferenceBasis& basis);

/// Every basis check: segment/triangle/tetrahedron orders 1..6, Hex8, Hex20; node
/// order against Gmsh's published tables; Vandermonde conditioning.
void add_basis_checks(Report& report);

}  // namespace hofem::verification
