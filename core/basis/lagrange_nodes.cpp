#include "basis/lagrange_nodes.hpp"
#include "basis/element_orders.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace hofem {

std::vector<std::array<int, 2>> triangle_lattice(int p) {
  if (p < 0) return {};
  if (p == 0) return {{0, 0}};
  const std::array<std::array<int, 2>, 3> v{{{0, 0}, {p, 0}, {0, p}}};
  std::vector<std::array<int, 2>> pts(v.begin(), v.end());
  const int edges[3][2] = {{0, 1}, {1, 2}, {2, 0}};
  for (const auto& e : edges)
    for (int i = 1; i < p; ++i)
      pts.push_back({v[e[0]][0] + i * (v[e[1]][0] - v[e[0]][0]) / p, v[e[0]][1] + i * (v[e[1]][1] - v[e[0]][1]) / p});
  for (const auto& q : triangle_lattice(p - 3)) pts.push_back({q[0] + 1, q[1] + 1});
  return pts;
}

std::vector<std::array<int, 3>> tetrahedron_lattice(int p) {
  if (p < 0) return {};
  if (p == 0) return {{0, 0, 0}};
  const std::array<std::array<int, 3>, 4> v{{{0, 0, 0}, {p, 0, 0}, {0, p, 0}, {0, 0, p}}};
  std::vector<std::array<int, 3>> pts(v.begin(), v.end());
  const int edges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}};
  for (const auto& e : edges)
    for (int i = 1; i < p; ++i) {
      std::array<int, 3> x{};
      for (int c = 0; c < 3; ++c) x[c] = v[e[0]][c] + i * (v[e[1]][c] - v[e[0]][c]) / p;
      pts.push_back(x);
    }
  const int faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {3, 1, 2}};
  const auto face_lattice = triangle_lattice(p - 3);
  for (const auto& f : faces)
    for (const auto& st : face_lattice) {
      std::array<int, 3> x{};
      for (int c = 0; c < 3; ++c)
        x[c] = v[f[0]][c] + ((st[0] + 1) * (v[f[1]][c] - v[f[0]][c]) + (st[1] + 1) * (v[f[2]][c] - v[f[0]][c])) / p;
      pts.push_back(x);
    }
  for (const auto& q : tetrahedron_lattice(p - 4)) pts.push_back({q[0] + 1, q[1] + 1, q[2] + 1});
  return pts;
}

Eigen::MatrixXd simplex_lagrange_nodes(CellType cell, int p) {
  if (p < 1) throw std::invalid_argument(fmt::format("Lagrange order must be >= 1, got {}", p));
  // Lattice points (in units of 1/p) as node coordinates, one column each.
  auto from_lattice = [p](const auto& lattice, int dim) {
    Eigen::MatrixXd x(dim, static_cast<Eigen::Index>(lattice.size()));
    for (size_t n = 0; n < lattice.size(); ++n)
      for (int c = 0; c < dim; ++c) x(c, n) = static_cast<double>(lattice[n][c]) / p;
    return x;
  };
  switch (cell) {
    case CellType::Segment: {
      Eigen::MatrixXd x(1, p + 1);
      x(0, 0) = -1.0;
      x(0, 1) = 1.0;
      for (int i = 1; i < p; ++i) x(0, i + 1) = -1.0 + 2.0 * i / p;
      return x;
    }
    case CellType::Triangle: return from_lattice(triangle_lattice(p), 2);
    case CellType::Tetrahedron: return from_lattice(tetrahedron_lattice(p), 3);
    default: throw std::invalid_argument(fmt::format("simplex_lagrange_nodes: {} is not a simplex", name(cell)));
  }
}

Eigen::MatrixXd hex_nodes(int order) {
  check_element_order(CellType::Hexahedron, order, "hex elements");
  Eigen::MatrixXd x = reference_vertices(CellType::Hexahedron);
  if (order == 1) return x;
  // Hex20 edge midpoints, Gmsh edge order (Geo/MHexahedron.h).
  const int edges[12][2] = {{0, 1}, {0, 3}, {0, 4}, {1, 2}, {1, 5}, {2, 3},
                            {2, 6}, {3, 7}, {4, 5}, {4, 7}, {5, 6}, {6, 7}};
  Eigen::MatrixXd y(3, 20);
  y.leftCols(8) = x;
  for (int e = 0; e < 12; ++e) y.col(8 + e) = 0.5 * (x.col(edges[e][0]) + x.col(edges[e][1]));
  return y;
}

}  // namespace hofem
