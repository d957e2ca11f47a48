#pragma once
// Equispaced Lagrange nodes in Gmsh's node order, for any order.
//
// Gmsh's rule (Numeric/pointsGenerators.cpp, gmshGenerateMonomials*; checked
// against Gmsh 4.7's getElementProperties output for Tri10/15/21, Tet20/35/56):
//   1. the vertices;
//   2. p-1 nodes on each edge, in edge order, running from the edge's first
//      vertex to its second: triangle edges 0->1, 1->2, 2->0; tetrahedron edges
//      0->1, 1->2, 2->0, 3->0, 3->2, 3->1;
//   3. triangle interior (p >= 3): the order p-3 triangle's nodes, recursively in
//      this same order, shifted one lattice step in from vertex 0;
//   4. tetrahedron faces (p >= 3), in order {0,2,1}, {0,1,3}, {0,3,2}, {3,1,2}:
//      node = f0 + ((s+1)(f1-f0) + (t+1)(f2-f0))/p over the order p-3 triangle's
//      lattice points (s, t) in their own Gmsh order;
//   5. tetrahedron volume (p >= 4): the order p-4 tetrahedron, recursively, shifted
//      by (1,1,1)/p.
// Segment nodes are on [-1, 1]: -1, 1, then the interior ones from -1 to 1.
#include "quadrature/cell_type.hpp"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace hofem {

/// Integer lattice points (coordinates in units of 1/p) of the order-p triangle, Gmsh order.
std::vector<std::array<int, 2>> triangle_lattice(int p);
/// Integer lattice points of the order-p tetrahedron, Gmsh order.
std::vector<std::array<int, 3>> tetrahedron_lattice(int p);

/// Nodes (dim x n) of the order-p Lagrange element on a simplex cell, Gmsh order.
Eigen::MatrixXd simplex_lagrange_nodes(CellType cell, int order);

/// Hex8 (order 1) or Hex20 (serendipity order 2) nodes on [-1,1]^3, Gmsh order.
Eigen::MatrixXd hex_nodes(int order);

}  // namespace hofem
