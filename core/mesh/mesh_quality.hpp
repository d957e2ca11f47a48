#pragma once
// Element quality: dihedral angles of the vertex tetrahedra and the sign of the
// isoparametric Jacobian at quadrature points. Inverted or degenerate elements
// are reported by index.
#include "mesh/mesh.hpp"

#include <Eigen/Core>

#include <vector>

namespace hofem {

struct MeshQuality {
  double min_dihedral_degrees = 0.0;  ///< tetrahedra only (vertex tets); 0 for hex meshes
  double max_dihedral_degrees = 0.0;
  double min_jacobian_ratio = 0.0;    ///< min over elements of min det J / max det J at quadrature points
  int worst_element = -1;             ///< element with the smallest Jacobian ratio
  int inverted_elements = 0;          ///< det J <= 0 somewhere
};

/// det J of an element's isoparametric map at the points where validity is
/// decided: the quadrature points of the stiffness rule (degree 2 * order) and
/// the vertices (a curved element can be valid at its quadrature points and fold
/// at a corner).
class ElementJacobians {
 public:
  ElementJacobians(CellType cell, int order);
  struct Extremes {
    double min, max;    ///< smallest and largest det J over the points
    const char* where;  ///< "quadrature point" or "vertex", of the minimum
    int index;          ///< which one
  };
  Extremes extremes(const Mesh& mesh, int element) const;

 private:
  std::vector<Eigen::MatrixXd> point_gradients_;  // reference gradients, quadrature points then vertices
  int quadrature_points_ = 0;
};

/// Measures every element; quadrature_degree < 0: 2 * order.
MeshQuality measure_quality(const Mesh& mesh, int quadrature_degree = -1);

/// Throws MeshError naming the first inverted (det J <= 0 at a quadrature point
/// or vertex) or degenerate (det J below 1e-12 of the mesh's typical scale)
/// element, with its index; also checks connectivity indices are in range.
void validate_mesh(const Mesh& mesh);

}  // namespace hofem
