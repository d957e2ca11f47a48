#pragma once
// The deformed boundary surface of a run as flat triangles, for the surface
// distance (surface_distance.hpp). A surface is a lattice of points given by
// (element, reference coordinates) - positions follow the run's own map and
// field, x = X(xi) + u(xi), so curved faces of higher-order elements and curved
// deformed faces are resolved by subdividing each face into s x s pieces:
//   - conforming meshes: the faces of the elements that belong to one element
//     only (tet faces, hex quads), subdivided in the element's reference cell;
//   - finite-cell runs: the embedded geometry's boundary triangles (straight in
//     the undeformed state), subdivided, and their lattice points located in the
//     background cells that integrate something (Longva et al. 2020 §5.3: the
//     embedded surface moves with the background field).
#include "embedded/embedded_points.hpp"
#include "mesh/mesh.hpp"
#include "study/surface_distance.hpp"

#include <array>
#include <vector>

namespace hofem {

struct SurfaceLattice {
  EmbeddedPointMap at;                         ///< every lattice point's element and xi
  std::vector<std::array<int, 3>> triangles;   ///< over the lattice points
};

/// The default subdivision of a face for a field of the given order: 1 for
/// linear tets (flat faces stay flat), 2 p otherwise (the chord of a degree-p
/// face over a piece of size h/s deviates by O((h/s)^2)).
int default_subdivisions(CellType cell, int order);

/// The boundary faces of a conforming mesh, each split into s x s pieces.
SurfaceLattice boundary_lattice(const Mesh& mesh, int subdivisions);

/// The boundary triangles of an embedded geometry (linear triangles in
/// undeformed coordinates, embedded/embedded_points.hpp: boundary_surface), each
/// split into s x s pieces, located in the background's active cells.
SurfaceLattice embedded_lattice(const Mesh& background, const Mesh& surface, const std::vector<char>& active,
                                int subdivisions);

/// The lattice's triangles at x = X(xi) + u(xi) for the field u (3 per node of `mesh`).
TriangleSurface deformed_surface(const Mesh& mesh, const SurfaceLattice& lattice, const Eigen::VectorXd& u);

}  // namespace hofem
