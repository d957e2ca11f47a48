#pragma once
// Element quality: dihedral angles of the vertex tetrahedra and the sign of the
// isoparametric Jacobian at quadrature points. Inverted or degenerate elements
// are reported by index.
#include "mesh/mesh.hpp"

namespace hofem {

struct MeshQuality {
  double min_dihedral_degrees = 0.0;  ///< tetrahedra only (vertex tets); 0 for hex meshes
  double max_dihedral_degrees = 0.0;
  double min_jacobian_ratio = 0.0;    ///< min over elements of min det J / max det J at quadrature points
  int worst_element = -1;             ///< element with the smallest Jacobian ratio
  int inverted_elements = 0;          ///< det J <= 0 somewhere
};

/// Measures every element; quadrature_degree < 0: 2 * order.
MeshQuality measure_quality(const Mesh& mesh, int quadrature_degree = -1);

/// Throws MeshError naming the first inverted (det J <= 0 at a quadrature point
/// or vertex) or degenerate (det J below 1e-12 of the mesh's typical scale)
/// element, with its index; also checks connectivity indices are in range.
void validate_mesh(const Mesh& mesh);

}  // namespace hofem
