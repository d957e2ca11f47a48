#include "embedded/embedded_points.hpp"

#include "basis/reference_basis.hpp"
#include "embedded/embedded_quadrature.hpp"
#include "embedded/finite_cell_quadrature.hpp"
#include "quadrature/cell_type.hpp"

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

// The active cells' bounding boxes (all nodes: a curved cell bulges past its
// vertices; curved cells' boxes get 5 % slack so boundary points of a curved face
// stay inside) in uniform buckets, ~cbrt(active cells) per axis; an inactive
// cell's box is left empty, so no bucket lists it.
BoxBucketGrid cell_grid(const Mesh& mesh, const std::vector<AffineFit>& fits, const std::vector<char>& active) {
  std::vector<Eigen::AlignedBox3d> boxes(mesh.num_elements());
  int count = 0;
  for (int e = 0; e < mesh.num_elements(); ++e) {
    if (!active.empty() && !active[e]) continue;
    for (int i = 0; i < mesh.nodes_per_element(); ++i)
      boxes[e].extend(Eigen::Vector3d(mesh.nodes.col(mesh.elements(i, e))));
    const double slack = fits[e].affine ? 1e-10 * fits[e].size : 0.05 * fits[e].size;
    boxes[e].min().array() -= slack;
    boxes[e].max().array() += slack;
    ++count;
  }
  if (count == 0) throw std::invalid_argument("locate_embedded_points: no active background cell");
  return BoxBucketGrid(std::move(boxes), std::max(1, static_cast<int>(std::cbrt(static_cast<double>(count)))));
}

double box_distance(const Eigen::Vector3d& X, const Eigen::AlignedBox3d& box) {
  return (box.min() - X).cwiseMax(X - box.max()).cwiseMax(0.0).norm();
}

// Appends the cells listed in the buckets at Chebyshev distance r from `home`.
void shell(const BoxBucketGrid& grid, const Eigen::Vector3i& home, int r, std::vector<int>& out) {
  const int n = grid.buckets_per_axis();
  for (int i = std::max(0, home.x() - r); i <= std::min(n - 1, home.x() + r); ++i)
    for (int j = std::max(0, home.y() - r); j <= std::min(n - 1, home.y() + r); ++j)
      for (int k = std::max(0, home.z() - r); k <= std::min(n - 1, home.z() + r); ++k)
        if (std::max({std::abs(i - home.x()), std::abs(j - home.y()), std::abs(k - home.z())}) == r)
          for (int e : grid.bucket(Eigen::Vector3i(i, j, k))) out.push_back(e);
}

constexpr double kInsideTol = 1e-10;  // reference-coordinate rounding of the inverse map

// The cell containing X, or -1; its reference coordinates in xi.
int containing_cell(const BoxBucketGrid& grid, CellMaps& maps, CellType cell, const Eigen::Vector3d& X,
                    Eigen::Vector3d& xi) {
  for (int e : grid.bucket(grid.bucket_of(X))) {
    if (!grid.box(e).contains(X)) continue;
    xi = maps.reference(e, X);
    if (inside(cell, xi, kInsideTol)) return e;
  }
  return -1;
}

// The nearest active cell, by the physical distance to its point at the clamped
// reference coordinates: shells of buckets outward from the point's own, one
// shell past the first that holds a cell (a cell's box may reach into a nearer
// bucket than the one of its nearest point, so this is the nearest among the
// cells near the point, not a global search).
int nearest_cell(const BoxBucketGrid& grid, CellMaps& maps, CellType cell, const Eigen::Vector3d& X,
                 Eigen::Vector3d& xi, std::vector<int>& candidates) {
  double best = std::numeric_limits<double>::infinity();
  const int n = grid.buckets_per_axis();
  int found = -1, last = n;
  const Eigen::Vector3i home = grid.bucket_of(X);
  for (int r = 0; r <= std::min(last, n); ++r) {
    candidates.clear();
    shell(grid, home, r, candidates);
    for (int e : candidates) {
      if (box_distance(X, grid.box(e)) >= best) continue;  // cannot be nearer
      const Eigen::Vector3d x = maps.reference(e, X);
      const double d = (maps.position(e, clamp_to_reference(cell, x)) - X).norm();
      if (d < best) {
        best = d;
        found = e;
        xi = x;
      }
    }
    if (!candidates.empty() && last == n) last = r + 1;
  }
  return found;
}

}  // namespace

EmbeddedPointMap locate_embedded_points(const Mesh& background, const Eigen::Matrix3Xd& points,
                                        const std::vector<char>& active) {
  const int ne = background.num_elements();
  if (!active.empty() && static_cast<int>(active.size()) != ne)
    throw std::invalid_argument(fmt::format("locate_embedded_points: {} activity flags for {} elements", active.size(), ne));
  if (!points.allFinite()) throw std::invalid_argument("locate_embedded_points: a point is not finite");
  std::vector<AffineFit> fits(ne);
  for (int e = 0; e < ne; ++e) {
    fits[e] = fit_affine_cell(background, e);
    if (fits[e].degenerate) throw std::invalid_argument(fmt::format("locate_embedded_points: element {} is degenerate", e));
  }
  const BoxBucketGrid grid = cell_grid(background, fits, active);

  EmbeddedPointMap out;
  const int np = static_cast<int>(points.cols());
  out.element.assign(np, -1);
  out.xi.resize(3, np);
  out.extrapolated.assign(np, 0);
#pragma omp parallel
  {
    CellMaps maps(background, fits);
    std::vector<int> candidates;
    Eigen::Vector3d xi;
#pragma omp for schedule(dynamic, 256)
    for (int q = 0; q < np; ++q) {
      int e = containing_cell(grid, maps, background.cell, points.col(q), xi);
      if (e < 0) {
        e = nearest_cell(grid, maps, background.cell, points.col(q), xi, candidates);
        out.extrapolated[q] = 1;
      }
      out.element[q] = e;
      out.xi.col(q) = xi;
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
  std::map<std::array<int, 3>, std::pair<int, std::array<int, 3>>> faces;  // sorted key -> (count, oriented)
  for (int e = 0; e < tets.num_elements(); ++e) {
    // Orientation from the actual vertex order (either handedness of input).
    Eigen::Matrix3d J;
    for (int k = 0; k < 3; ++k) J.col(k) = tets.nodes.col(tets.elements(k + 1, e)) - tets.nodes.col(tets.elements(0, e));
    const bool flip = J.determinant() < 0.0;
    for (const auto& f : kTetrahedronFaces) {
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
  Mesh surface;
  surface.cell = CellType::Triangle;
  surface.order = 1;
  surface.elements.resize(3, static_cast<Eigen::Index>(tris.size()));
  std::vector<int> new_id(tets.num_nodes(), -1), old_id;
  for (size_t t = 0; t < tris.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int v = tris[t][k];
      if (new_id[v] < 0) {
        new_id[v] = static_cast<int>(old_id.size());
        old_id.push_back(v);
      }
      surface.elements(k, static_cast<Eigen::Index>(t)) = new_id[v];
    }
  surface.nodes = tets.nodes(Eigen::all, old_id);
  if (vertex_of) *vertex_of = std::move(old_id);
  return surface;
}

}  // namespace hofem
