#include "mesh/box_mesh.hpp"

#include "mesh/mesh_upgrade.hpp"

#include <fmt/format.h>

#include <cmath>

namespace hofem {

namespace {

void check_box(const BoxSpec& b) {
  for (int c = 0; c < 3; ++c) {
    if (b.cells[c] < 1) throw MeshError(fmt::format("box mesh: cells[{}] must be >= 1, got {}", c, b.cells[c]));
    if (!(b.upper[c] > b.lower[c]) || !std::isfinite(b.lower[c]) || !std::isfinite(b.upper[c]))
      throw MeshError(fmt::format("box mesh: need lower < upper in direction {}, got [{}, {}]", c, b.lower[c], b.upper[c]));
  }
}

Eigen::Matrix3Xd lattice_nodes(const BoxSpec& b) {
  const int nx = b.cells[0] + 1, ny = b.cells[1] + 1, nz = b.cells[2] + 1;
  Eigen::Matrix3Xd x(3, nx * ny * nz);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const int id = i + nx * (j + ny * k);
        const int idx[3] = {i, j, k};
        for (int c = 0; c < 3; ++c)
          x(c, id) = b.lower[c] + (b.upper[c] - b.lower[c]) * idx[c] / b.cells[c];
      }
  return x;
}

// The 8 corner ids of cube (i, j, k) in Gmsh Hex8 order.
std::array<int, 8> cube_corners(const BoxSpec& b, int i, int j, int k) {
  const int nx = b.cells[0] + 1, ny = b.cells[1] + 1;
  auto id = [&](int a, int c, int d) { return (i + a) + nx * ((j + c) + ny * (k + d)); };
  return {id(0, 0, 0), id(1, 0, 0), id(1, 1, 0), id(0, 1, 0), id(0, 0, 1), id(1, 0, 1), id(1, 1, 1), id(0, 1, 1)};
}

}  // namespace

// Node sets of the box faces, by coordinates (exact for nodes generated on the
// faces: they are computed from the bounds without rounding across a face).
static void assign_box_node_sets(Mesh& mesh, const BoxSpec& b) {
  const char* names[3][2] = {{"xmin", "xmax"}, {"ymin", "ymax"}, {"zmin", "zmax"}};
  mesh.node_sets.clear();
  std::vector<int> boundary;
  for (int n = 0; n < mesh.num_nodes(); ++n) {
    bool on = false;
    for (int c = 0; c < 3; ++c) {
      const double tol = 1e-12 * (b.upper[c] - b.lower[c]);
      if (std::fabs(mesh.nodes(c, n) - b.lower[c]) <= tol) mesh.node_sets[names[c][0]].push_back(n), on = true;
      if (std::fabs(mesh.nodes(c, n) - b.upper[c]) <= tol) mesh.node_sets[names[c][1]].push_back(n), on = true;
    }
    if (on) boundary.push_back(n);
  }
  mesh.node_sets["boundary"] = std::move(boundary);
}

// The order-1 mesh of box b: each lattice cell, in lattice order, gives the
// elements of `per_cell` (their nodes as indices into its cube_corners).
template <int Nodes, int PerCell>
static Mesh box_linear_mesh(const BoxSpec& b, CellType cell, const int (&per_cell)[PerCell][Nodes]) {
  check_box(b);
  Mesh m;
  m.cell = cell;
  m.order = 1;
  m.nodes = lattice_nodes(b);
  m.elements.resize(Nodes, PerCell * b.cells[0] * b.cells[1] * b.cells[2]);
  int e = 0;
  for (int k = 0; k < b.cells[2]; ++k)
    for (int j = 0; j < b.cells[1]; ++j)
      for (int i = 0; i < b.cells[0]; ++i) {
        const auto c = cube_corners(b, i, j, k);
        for (const auto& t : per_cell) {
          for (int v = 0; v < Nodes; ++v) m.elements(v, e) = c[t[v]];
          ++e;
        }
      }
  assign_box_node_sets(m, b);
  return m;
}

Mesh box_tet_mesh(const BoxSpec& b) {
  // Six tetrahedra sharing the diagonal c0-c6, each positively oriented.
  const int tets[6][4] = {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6}, {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}};
  return box_linear_mesh(b, CellType::Tetrahedron, tets);
}

Mesh box_hex_mesh(const BoxSpec& b) {
  const int hex[1][8] = {{0, 1, 2, 3, 4, 5, 6, 7}};
  return box_linear_mesh(b, CellType::Hexahedron, hex);
}

Mesh box_mesh(const BoxSpec& b, CellType cell, int order) {
  nodes_per_element(cell, order);  // validates (cell, order)
  Mesh m = cell == CellType::Tetrahedron ? box_tet_mesh(b) : box_hex_mesh(b);
  if (order > 1) {
    m = upgrade_order(m, order);
    assign_box_node_sets(m, b);
  }
  return m;
}

}  // namespace hofem
