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

// The map X(xi) = sum_i N_i(xi) X_i of one cell and its inverse: A^-1 (X - X0)
// for affine cells, Newton's method on the isoparametric map from the affine
// fit's guess for curved ones (Longva et al. 2020 §4.5 inverts the map the same
// way). Each thread uses its own copy (scratch arrays); the fits are shared.
class CellMaps {
 public:
  explicit CellMaps(const Mesh& mesh, const std::vector<AffineFit>& fits)
      : mesh_(mesh), basis_(lagrange_basis(mesh.cell, mesh.order)), fits_(fits), N_(basis_.size()),
        dN_(basis_.size(), 3) {}
  Eigen::Vector3d position(int e, const Eigen::Vector3d& xi) {
    if (fits_[e].affine) return fits_[e].map.origin + fits_[e].map.A * xi;
    basis_.evaluate(xi, N_);
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int i = 0; i < basis_.size(); ++i) x += N_[i] * mesh_.nodes.col(mesh_.elements(i, e));
    return x;
  }
  Eigen::Vector3d reference(int e, const Eigen::Vector3d& X) {
    const AffineFit& fit = fits_[e];
    Eigen::Vector3d xi = fit.map.reference(X);
    if (fit.affine) return xi;
    // Newton: quadratic convergence from the affine guess inside well-shaped
    // cells; 1e-13 of the cell's size is round-off. Outside the cell (the
    // nearest-cell search) it may stall: the last iterate is a fair guess there.
    for (int it = 0; it < 30; ++it) {
      basis_.evaluate(xi, N_);
      basis_.gradients(xi, dN_);
      Eigen::Vector3d x = Eigen::Vector3d::Zero();
      Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
      for (int i = 0; i < basis_.size(); ++i) {
        const Eigen::Vector3d Xi = mesh_.nodes.col(mesh_.elements(i, e));
        x += N_[i] * Xi;
        J += Xi * dN_.row(i);
      }
      const Eigen::Vector3d step = J.partialPivLu().solve(X - x);
      if (!step.allFinite()) break;
      xi += step;
      if (step.norm() < 1e-13 || xi.norm() > 1e3) break;
    }
    return xi;
  }

 private:
  const Mesh& mesh_;
  const ReferenceBasis& basis_;
  const std::vector<AffineFit>& fits_;
  Eigen::VectorXd N_;
  Eigen::MatrixXd dN_;
};

double box_distance(const Eigen::Vector3d& X, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  return (lo - X).cwiseMax(X - hi).cwiseMax(0.0).norm();
}

}  // namespace

EmbeddedPointMap locate_embedded_points(const Mesh& background, const Eigen::Matrix3Xd& points,
                                        const std::vector<char>& active) {
  const int ne = background.num_elements();
  if (!active.empty() && static_cast<int>(active.size()) != ne)
    throw std::invalid_argument(fmt::format("locate_embedded_points: {} activity flags for {} elements", active.size(), ne));
  if (!points.allFinite()) throw std::invalid_argument("locate_embedded_points: a point is not finite");
  auto is_active = [&](int e) { return active.empty() || active[e]; };
  std::vector<AffineFit> fits(ne);
  std::vector<int> cells;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::max()), hi = -lo;
  std::vector<Eigen::Vector3d> cell_lo(ne), cell_hi(ne);
  for (int e = 0; e < ne; ++e) {
    fits[e] = fit_affine_cell(background, e);
    if (fits[e].degenerate) throw std::invalid_argument(fmt::format("locate_embedded_points: element {} is degenerate", e));
    // All nodes: a curved cell bulges past its vertices (by less than its own
    // size: the slack below keeps boundary points of a curved face inside).
    cell_lo[e] = cell_hi[e] = background.nodes.col(background.elements(0, e));
    for (int i = 1; i < background.nodes_per_element(); ++i) {
      cell_lo[e] = cell_lo[e].cwiseMin(background.nodes.col(background.elements(i, e)));
      cell_hi[e] = cell_hi[e].cwiseMax(background.nodes.col(background.elements(i, e)));
    }
    const double slack = fits[e].affine ? 1e-10 * fits[e].size : 0.05 * fits[e].size;
    cell_lo[e].array() -= slack;
    cell_hi[e].array() += slack;
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
  // The cells listed in the buckets at Chebyshev distance r from `home`.
  auto shell = [&](const Eigen::Vector3i& home, int r, std::vector<int>& out) {
    for (int i = std::max(0, home.x() - r); i <= std::min(n - 1, home.x() + r); ++i)
      for (int j = std::max(0, home.y() - r); j <= std::min(n - 1, home.y() + r); ++j)
        for (int k = std::max(0, home.z() - r); k <= std::min(n - 1, home.z() + r); ++k)
          if (std::max({std::abs(i - home.x()), std::abs(j - home.y()), std::abs(k - home.z())}) == r)
            for (int e : buckets[(static_cast<size_t>(i) * n + j) * n + k]) out.push_back(e);
  };

  EmbeddedPointMap out;
  const int np = static_cast<int>(points.cols());
  out.element.assign(np, -1);
  out.xi.resize(3, np);
  out.extrapolated.assign(np, 0);
  constexpr double kInsideTol = 1e-10;  // reference-coordinate rounding of the inverse map
#pragma omp parallel
  {
    CellMaps maps(background, fits);
    std::vector<int> candidates;
#pragma omp for schedule(dynamic, 256)
    for (int q = 0; q < np; ++q) {
      const Eigen::Vector3d X = points.col(q);
      const Eigen::Vector3i home = bucket(X);
      for (int e : buckets[(static_cast<size_t>(home.x()) * n + home.y()) * n + home.z()]) {
        if ((X.array() < cell_lo[e].array()).any() || (X.array() > cell_hi[e].array()).any()) continue;
        const Eigen::Vector3d xi = maps.reference(e, X);
        if (inside(background.cell, xi, kInsideTol)) {
          out.element[q] = e;
          out.xi.col(q) = xi;
          break;
        }
      }
      if (out.element[q] >= 0) continue;
      // The nearest active cell, by the physical distance to its point at the
      // clamped reference coordinates: shells of buckets outward from the point's
      // own, one shell past the first that holds a cell (a cell's box may reach
      // into a nearer bucket than the one of its nearest point, so this is the
      // nearest among the cells near the point, not a global search).
      double best = std::numeric_limits<double>::infinity();
      int last = n;
      for (int r = 0; r <= std::min(last, n); ++r) {
        candidates.clear();
        shell(home, r, candidates);
        for (int e : candidates) {
          if (box_distance(X, cell_lo[e], cell_hi[e]) >= best) continue;  // cannot be nearer
          const Eigen::Vector3d xi = maps.reference(e, X);
          const double d = (maps.position(e, clamp_to_reference(background.cell, xi)) - X).norm();
          if (d < best) {
            best = d;
            out.element[q] = e;
            out.xi.col(q) = xi;
          }
        }
        if (!candidates.empty() && last == n) last = r + 1;
      }
      out.extrapolated[q] = 1;
    }
  }
  out.num_extrapolated = static_cast<int>(std::count(out.extrapolated.begin(), out.extrapolated.end(), 1));
  return out;
}

Eigen::Matrix3Xd interpolate_at_points(const Mesh& background, const EmbeddedPointMap& map, const Eigen::VectorXd& u) {
  return evaluate_at_points(background, map, u, false).value;
}

PointValues evaluate_at_points(const Mesh& mesh, const EmbeddedPointMap& map, const Eigen::VectorXd& u,
                               bool with_gradient) {
  if (u.size() != 3 * mesh.num_nodes())
    throw std::invalid_argument(fmt::format("evaluate_at_points: field has {} values, the mesh needs {}", u.size(),
                                            3 * mesh.num_nodes()));
  const ReferenceBasis& basis = lagrange_basis(mesh.cell, mesh.order);
  PointValues out;
  out.value = Eigen::Matrix3Xd::Zero(3, map.size());
  if (with_gradient) out.gradient.assign(map.size(), Eigen::Matrix3d::Zero());
#pragma omp parallel
  {
  Eigen::VectorXd N(basis.size());
  Eigen::MatrixXd dN(basis.size(), 3);
#pragma omp for schedule(static)
  for (int q = 0; q < map.size(); ++q) {
    basis.evaluate(map.xi.col(q), N);
    const int e = map.element[q];
    for (int i = 0; i < basis.size(); ++i) out.value.col(q) += N[i] * u.segment<3>(3 * mesh.elements(i, e));
    if (!with_gradient) continue;
    // grad u = sum_i u_i (dN_i/dxi J^-1), J = dX/dxi of the isoparametric map.
    basis.gradients(map.xi.col(q), dN);
    Eigen::Matrix3d J = Eigen::Matrix3d::Zero(), G = Eigen::Matrix3d::Zero();
    for (int i = 0; i < basis.size(); ++i) {
      J += mesh.nodes.col(mesh.elements(i, e)) * dN.row(i);
      G += u.segment<3>(3 * mesh.elements(i, e)) * dN.row(i);
    }
    out.gradient[q] = G * J.inverse();
  }
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
