#include "study/surface_sampling.hpp"

#include "basis/reference_basis.hpp"
#include "quadrature/cell_type.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>

namespace hofem {

namespace {

// Lattice of a triangle a, b, c split into s x s pieces: points a + (i/s)(b - a)
// + (j/s)(c - a), i + j <= s, appended to `points`; triangles appended too.
void triangle_lattice(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, int s,
                      std::vector<Eigen::Vector3d>& points, std::vector<std::array<int, 3>>& triangles) {
  const int first = static_cast<int>(points.size());
  std::vector<int> row_start(s + 2);
  for (int j = 0, id = first; j <= s; ++j) {
    row_start[j] = id;
    for (int i = 0; i + j <= s; ++i, ++id) points.push_back(a + (b - a) * i / s + (c - a) * j / s);
  }
  auto at = [&](int i, int j) { return row_start[j] + i; };
  for (int j = 0; j < s; ++j)
    for (int i = 0; i + j < s; ++i) {
      triangles.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
      if (i + j + 1 < s) triangles.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
    }
}

// Lattice of a planar quad c0 c1 c2 c3 (bilinear in the parameters) split into s x s squares of two triangles.
void quad_lattice(const std::array<Eigen::Vector3d, 4>& c, int s, std::vector<Eigen::Vector3d>& points,
                  std::vector<std::array<int, 3>>& triangles) {
  const int first = static_cast<int>(points.size());
  for (int j = 0; j <= s; ++j)
    for (int i = 0; i <= s; ++i) {
      const double x = static_cast<double>(i) / s, y = static_cast<double>(j) / s;
      points.push_back((1 - x) * (1 - y) * c[0] + x * (1 - y) * c[1] + x * y * c[2] + (1 - x) * y * c[3]);
    }
  auto at = [&](int i, int j) { return first + j * (s + 1) + i; };
  for (int j = 0; j < s; ++j)
    for (int i = 0; i < s; ++i) {
      triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
}

void check_subdivisions(int s) {
  if (s < 1 || s > 64) throw std::invalid_argument("surface lattice: subdivisions must be in [1, 64]");
}

}  // namespace

int default_subdivisions(CellType cell, int order) {
  return cell == CellType::Tetrahedron && order == 1 ? 1 : 2 * order;
}

SurfaceLattice boundary_lattice(const Mesh& mesh, int s) {
  check_subdivisions(s);
  const bool tet = mesh.cell == CellType::Tetrahedron;
  const Eigen::MatrixXd& ref = lagrange_basis(mesh.cell, mesh.order).nodes();
  // Faces keyed by their sorted vertex ids; a boundary face belongs to one element.
  std::map<std::vector<int>, std::pair<int, std::pair<int, int>>> faces;  // key -> (count, (element, face))
  const int nf = tet ? 4 : 6;
  for (int e = 0; e < mesh.num_elements(); ++e)
    for (int f = 0; f < nf; ++f) {
      std::vector<int> key;
      if (tet) for (int v : kTetrahedronFaces[f]) key.push_back(mesh.elements(v, e));
      else for (int v : kHexahedronFaces[f]) key.push_back(mesh.elements(v, e));
      std::sort(key.begin(), key.end());
      auto [it, fresh] = faces.try_emplace(std::move(key), 0, std::make_pair(e, f));
      ++it->second.first;
    }
  SurfaceLattice out;
  std::vector<Eigen::Vector3d> xi;
  std::vector<int> element;
  for (const auto& [key, value] : faces) {
    if (value.first != 1) continue;
    const auto [e, f] = value.second;
    if (tet)
      triangle_lattice(ref.col(kTetrahedronFaces[f][0]), ref.col(kTetrahedronFaces[f][1]), ref.col(kTetrahedronFaces[f][2]), s, xi,
                       out.triangles);
    else
      quad_lattice({ref.col(kHexahedronFaces[f][0]), ref.col(kHexahedronFaces[f][1]), ref.col(kHexahedronFaces[f][2]),
                    ref.col(kHexahedronFaces[f][3])},
                   s, xi, out.triangles);
    element.resize(xi.size(), e);
  }
  out.at.element = std::move(element);
  out.at.xi.resize(3, static_cast<Eigen::Index>(xi.size()));
  for (size_t i = 0; i < xi.size(); ++i) out.at.xi.col(static_cast<Eigen::Index>(i)) = xi[i];
  out.at.extrapolated.assign(xi.size(), 0);
  return out;
}

SurfaceLattice embedded_lattice(const Mesh& background, const Mesh& surface, const std::vector<char>& active, int s) {
  check_subdivisions(s);
  if (surface.cell != CellType::Triangle || surface.order != 1)
    throw std::invalid_argument("embedded_lattice: the embedded surface must be linear triangles");
  std::vector<Eigen::Vector3d> X;
  SurfaceLattice out;
  for (int t = 0; t < surface.num_elements(); ++t)
    triangle_lattice(surface.nodes.col(surface.elements(0, t)), surface.nodes.col(surface.elements(1, t)),
                     surface.nodes.col(surface.elements(2, t)), s, X, out.triangles);
  Eigen::Matrix3Xd points(3, static_cast<Eigen::Index>(X.size()));
  for (size_t i = 0; i < X.size(); ++i) points.col(static_cast<Eigen::Index>(i)) = X[i];
  out.at = locate_embedded_points(background, points, active);
  return out;
}

TriangleSurface deformed_surface(const Mesh& mesh, const SurfaceLattice& lattice, const Eigen::VectorXd& u) {
  const Eigen::VectorXd X = Eigen::Map<const Eigen::VectorXd>(mesh.nodes.data(), 3 * mesh.num_nodes());
  TriangleSurface out;
  out.points = evaluate_at_points(mesh, lattice.at, X + u, false).value;
  out.triangles = lattice.triangles;
  return out;
}

}  // namespace hofem
