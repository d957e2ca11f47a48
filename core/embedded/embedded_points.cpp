#include "embedded/embedded_points.hpp"

#include "basis/reference_basis.hpp"
#include "embedded/finite_cell_quadrature.hpp"

#include <Eigen/LU>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

namespace hofem {

namespace {

/// The point of the reference cell nearest to xi in reference coordinates
/// (clamping: exact for the hex box; for the tet a good enough guide to "nearest").
Eigen::Vector3d clamp_to_reference(CellType cell, const Eigen::Vector3d& xi) {
  if (cell == CellType::Hexahedron) return xi.cwiseMax(-1.0).cwiseMin(1.0);
  Eigen::Vector3d c = xi.cwiseMax(0.0);
  const double s = c.sum();
  if (s > 1.0) c /= s;
  return c;
}

bool inside(CellType cell, const Eigen::Vector3d& xi, double tol) {
  if (cell == CellType::Hexahedron) return (xi.array().abs() <= 1.0 + tol).all();
  return (xi.array() >= -tol).all() && xi.sum() <= 1.0 + tol;
}

}  // namespace

EmbeddedPointMap locate_embedded_points(const Mesh& background, const Eigen::Matrix3Xd& points,
                                        const std::vector<char>& active) {
  const int ne = background.num_elements();
  if (!active.empty() && static_cast<int>(active.size()) != ne)
    throw std::invalid_argument(fmt::format("locate_embedded_points: {} activity flags for {} elements", active.size(), ne));
  if (!points.allFinite()) throw std::invalid_argument("locate_embedded_points: a point is not finite");
  auto is_active = [&](int e) { return active.empty() || active[e]; };
  std::vector<AffineCell> maps;
  std::vector<int> cells;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::max()), hi = -lo;
  std::vector<Eigen::Vector3d> cell_lo(ne), cell_hi(ne);
  maps.reserve(ne);
  for (int e = 0; e < ne; ++e) {
    maps.push_back(affine_cell(background, e));
    cell_lo[e] = cell_hi[e] = background.nodes.col(background.elements(0, e));
    for (int i = 1; i < background.vertices_per_element(); ++i) {
      cell_lo[e] = cell_lo[e].cwiseMin(background.nodes.col(background.elements(i, e)));
      cell_hi[e] = cell_hi[e].cwiseMax(background.nodes.col(background.elements(i, e)));
    }
    if (is_active(e)) {
      cells.push_back(e);
      lo = lo.cwiseMin(cell_lo[e]);
      hi = hi.cwiseMax(cell_hi[e]);
    }
  }
  if (cells.empty()) throw std::invalid_argument("locate_embedded_points: no active background cell");
  // Uniform buckets over the active cells' bounding boxes.
  const int n = std::max(1, static_cast<int>(std::cbrt(static_cast<double>(cells.size()))));
  const Eigen::Vector3d size = ((hi - lo) / n).cwiseMax(1e-300);
  auto bucket = [&](const Eigen::Vector3d& x) {
    return ((x - lo).cwiseQuotient(size)).array().floor().cast<int>().cwiseMax(0).cwiseMin(n - 1).matrix().eval();
  };
  std::vector<std::vector<int>> buckets(static_cast<size_t>(n) * n * n);
  for (int e : cells) {
    const Eigen::Vector3i a = bucket(cell_lo[e]), b = bucket(cell_hi[e]);
    for (int i = a.x(); i <= b.x(); ++i)
      for (int j = a.y(); j <= b.y(); ++j)
        for (int k = a.z(); k <= b.z(); ++k) buckets[(static_cast<size_t>(i) * n + j) * n + k].push_back(e);
  }

  EmbeddedPointMap out;
  const int np = static_cast<int>(points.cols());
  out.element.assign(np, -1);
  out.xi.resize(3, np);
  out.extrapolated.assign(np, 0);
  constexpr double kInsideTol = 1e-10;  // reference-coordinate rounding of A^-1 (X - X0)
  for (int q = 0; q < np; ++q) {
    const Eigen::Vector3d X = points.col(q);
    const bool in_box = (X.array() >= lo.array() - 1e-12 * size.norm()).all() &&
                        (X.array() <= hi.array() + 1e-12 * size.norm()).all();
    const Eigen::Vector3i b = bucket(X);
    const size_t home = (static_cast<size_t>(b.x()) * n + b.y()) * n + b.z();
    if (in_box)
      for (int e : buckets[home]) {
        const Eigen::Vector3d xi = maps[e].reference(X);
        if (inside(background.cell, xi, kInsideTol)) {
          out.element[q] = e;
          out.xi.col(q) = xi;
          break;
        }
      }
    if (out.element[q] >= 0) continue;
    // Nearest active cell, by the physical distance to the clamped reference point.
    double best = std::numeric_limits<double>::infinity();
    for (int e : cells) {
      const Eigen::Vector3d xi = maps[e].reference(X);
      const double d = (maps[e].A * (xi - clamp_to_reference(background.cell, xi))).norm();
      if (d < best) {
        best = d;
        out.element[q] = e;
        out.xi.col(q) = xi;
      }
    }
    out.extrapolated[q] = 1;
    ++out.num_extrapolated;
  }
  return out;
}

Eigen::Matrix3Xd interpolate_at_points(const Mesh& background, const EmbeddedPointMap& map, const Eigen::VectorXd& u) {
  if (u.size() != 3 * background.num_nodes())
    throw std::invalid_argument(fmt::format("interpolate_at_points: field has {} values, the background needs {}", u.size(),
                                            3 * background.num_nodes()));
  const ReferenceBasis& basis = lagrange_basis(background.cell, background.order);
  Eigen::Matrix3Xd out = Eigen::Matrix3Xd::Zero(3, map.size());
  Eigen::VectorXd N(basis.size());
  for (int q = 0; q < map.size(); ++q) {
    basis.evaluate(map.xi.col(q), N);
    const int e = map.element[q];
    for (int i = 0; i < basis.size(); ++i) out.col(q) += N[i] * u.segment<3>(3 * background.elements(i, e));
  }
  return out;
}

Mesh boundary_surface(const Mesh& tets, std::vector<int>* vertex_of) {
  if (tets.cell != CellType::Tetrahedron) throw std::invalid_argument("boundary_surface: needs a tetrahedral mesh");
  // Gmsh tet faces opposite each vertex, ordered so that the normal points away from it.
  constexpr std::array<std::array<int, 3>, 4> kFaces{{{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}}};
  std::map<std::array<int, 3>, std::pair<int, std::array<int, 3>>> faces;  // sorted key -> (count, oriented)
  for (int e = 0; e < tets.num_elements(); ++e) {
    // Orientation from the actual vertex order (either handedness of input).
    Eigen::Matrix3d J;
    for (int k = 0; k < 3; ++k) J.col(k) = tets.nodes.col(tets.elements(k + 1, e)) - tets.nodes.col(tets.elements(0, e));
    const bool flip = J.determinant() < 0.0;
    for (const auto& f : kFaces) {
      std::array<int, 3> v{tets.elements(f[0], e), tets.elements(f[1], e), tets.elements(f[2], e)};
      if (flip) std::swap(v[1], v[2]);
      std::array<int, 3> key = v;
      std::sort(key.begin(), key.end());
      auto [it, fresh] = faces.try_emplace(key, 0, v);
      ++it->second.first;
    }
  }
  std::vector<std::array<int, 3>> tris;
  for (const auto& [key, value] : faces)
    if (value.first == 1) tris.push_back(value.second);
  std::vector<int> new_id(tets.num_nodes(), -1), old_id;
  for (auto& t : tris)
    for (int& v : t) {
      if (new_id[v] < 0) {
        new_id[v] = static_cast<int>(old_id.size());
        old_id.push_back(v);
      }
      v = new_id[v];
    }
  Mesh surface;
  surface.cell = CellType::Triangle;
  surface.order = 1;
  surface.nodes.resize(3, static_cast<Eigen::Index>(old_id.size()));
  for (size_t i = 0; i < old_id.size(); ++i) surface.nodes.col(static_cast<Eigen::Index>(i)) = tets.nodes.col(old_id[i]);
  surface.elements.resize(3, static_cast<Eigen::Index>(tris.size()));
  for (size_t t = 0; t < tris.size(); ++t)
    for (int k = 0; k < 3; ++k) surface.elements(k, static_cast<Eigen::Index>(t)) = tris[t][k];
  if (vertex_of) *vertex_of = std::move(old_id);
  return surface;
}

}  // namespace hofem
