#pragma once
// Structured meshes of an axis-aligned box.
#include "mesh/mesh.hpp"

#include <array>

namespace hofem {

struct BoxSpec {
  std::array<double, 3> lower{0.0, 0.0, 0.0};
  std::array<double, 3> upper{1.0, 1.0, 1.0};
  std::array<int, 3> cells{1, 1, 1};  ///< cubes (hexahedra) per direction
};

/// Linear tetrahedra: each cube split into 6 tetrahedra around its (0,0,0)-(1,1,1)
/// diagonal (Kuhn / Freudenthal triangulation: every cube uses the same diagonal
/// direction, so the face diagonals of neighbouring cubes match and the mesh is
/// conforming). All tetrahedra positively oriented.
/// Node sets: "boundary", "xmin", "xmax", "ymin", "ymax", "zmin", "zmax".
Mesh box_tet_mesh(const BoxSpec& box);

/// Hex8 mesh of the box, same node sets.
Mesh box_hex_mesh(const BoxSpec& box);

/// Box mesh of any supported element: cell Tetrahedron with order p >= 1 (the
/// linear mesh upgraded with shared edge/face nodes) or Hexahedron with order 1/2.
/// The node sets are recomputed geometrically so they include high-order nodes.
Mesh box_mesh(const BoxSpec& box, CellType cell, int order);

/// Unit cube [0,1]^3 with n cells per side.
inline BoxSpec unit_cube(int n) { return BoxSpec{{0, 0, 0}, {1, 1, 1}, {n, n, n}}; }

}  // namespace hofem
