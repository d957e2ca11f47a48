#pragma once
// Finite-cell quadrature (second seed §4.5): for every cell of a background mesh,
// a rule of degree m over the part of the embedded geometry inside it, in the
// cell's reference coordinates, ready for Assembler::set_element_quadrature.
//
// Background cells are the axis-aligned boxes of a structured Hex8/Hex20 grid
// (box_mesh), whose map to [-1, 1]^3 is affine and diagonal, so the cell's planar
// faces are its half-spaces and the map back to reference coordinates is exact.
// Non-affine hexahedra would need their faces' planes of the undeformed reference
// geometry or a subdivision into tets; they are refused (not built).
#include "basis/basis_tabulation.hpp"
#include "embedded/tet_clipping.hpp"
#include "mesh/mesh.hpp"

#include <memory>
#include <span>
#include <vector>

namespace hofem {

struct CellQuadrature {
  /// Per element: its rule (empty where the geometry does not reach the cell).
  std::vector<std::shared_ptr<const ElementQuadrature>> rules;
  /// Per element: volume of (geometry ∩ cell) / volume of the cell.
  std::vector<double> volume_fraction;
  /// Quadrature points before any simplification, summed over cells.
  long long points = 0;
};

/// Throws std::invalid_argument for a background that is not a grid of
/// axis-aligned Hex8/Hex20 boxes.
CellQuadrature finite_cell_quadrature(const Mesh& background, std::span<const Tetrahedron> geometry, int degree);

/// Second seed §5.3, applied to the rules of finite_cell_quadrature:
///  - cells whose volume fraction is positive but below drop_fraction are
///    dropped (their rule emptied; listed in `dropped`): a sliver's stiffness is
///    too small to control its DOFs;
///  - every other cut cell (fraction < 1) gets the standard Gauss points of the
///    full cell with weights scaled by `stabilisation`, so that its stiffness
///    stays positive definite however small the cut part is (the fictitious-domain
///    stiffness of the finite cell method).
struct FiniteCellStabilisation {
  double drop_fraction = 1e-4;
  double stabilisation = 1e-6;
  int gauss_degree = -1;  ///< of the added points; < 0: 2 p (the standard stiffness rule)
};
struct StabilisedCells {
  std::vector<int> dropped;     ///< elements dropped for a volume fraction below drop_fraction
  std::vector<int> stabilised;  ///< cut elements that received the scaled Gauss points
};
StabilisedCells stabilise_finite_cells(const Mesh& background, CellQuadrature& cells,
                                       const FiniteCellStabilisation& options = {});

/// Nodes of the elements with a non-empty rule: the DOFs the finite-cell system
/// has; the others carry no stiffness or mass and are left out (or extrapolated).
std::vector<int> active_nodes(const Mesh& background, const CellQuadrature& cells);

}  // namespace hofem
