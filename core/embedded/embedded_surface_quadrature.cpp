#include "embedded/embedded_surface_quadrature.hpp"

#include "basis/reference_basis.hpp"
#include "embedded/embedded_points.hpp"
#include "embedded/embedded_quadrature.hpp"
#include "embedded/finite_cell_quadrature.hpp"
#include "quadrature/rule_library.hpp"

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <stdexcept>

namespace hofem {

namespace {

/// A vertex within this distance of a cell's face plane counts as on it, for
/// clipping and for the rule that gives a triangle in a face to one cell. The
/// half-spaces of cell_half_spaces are in reference units (the hex is [-1, 1]^3),
/// so this is relative to the cell's size, far above the rounding of a vertex's
/// reference coordinates (~1e-16: a flat face on the grid plane z = 0 of a grid
/// with h = 1/6 came out at +2e-16, "outside", and was lost without it) and far
/// below any real cut.
constexpr double kOnFace = 1e-12;

/// A piece of a triangle in one cell: a point set appended to `out`.
struct CellPoints {
  std::vector<Eigen::Vector3d> points, normals;
  std::vector<double> weights;
};

/// True if the clipped polygon lies in one of the cell's face planes on the side
/// away from the body (the face's outward normal opposes the triangle's): the
/// neighbour across that face takes it instead.
bool belongs_to_neighbour(const ConvexPolygon& piece, const std::vector<HalfSpace>& planes,
                          const Eigen::Vector3d& normal) {
  for (const HalfSpace& h : planes) {
    bool on_plane = true;
    for (const Eigen::Vector3d& x : piece) on_plane = on_plane && std::abs(h.signed_distance(x)) <= kOnFace;
    if (on_plane) return h.n.dot(normal) <= 0.0;
  }
  return false;
}

/// Appends the rule `ref` mapped onto the fan triangles of `piece`.
void add_piece(const ConvexPolygon& piece, const Eigen::Vector3d& normal, double min_area, const QuadratureRule& ref,
               CellPoints& out) {
  const double ref_area = ref.weights.sum();  // 1/2 on the reference triangle
  for (size_t k = 1; k + 1 < piece.size(); ++k) {
    const Eigen::Vector3d a = piece[0], b = piece[k] - a, c = piece[k + 1] - a;
    const double area = 0.5 * b.cross(c).norm();
    if (!(area > min_area)) continue;  // a sliver from a vertex on a face: no area
    for (int q = 0; q < ref.size(); ++q) {
      out.points.push_back(a + b * ref.points(0, q) + c * ref.points(1, q));
      out.normals.push_back(normal);
      out.weights.push_back(area * ref.weights[q] / ref_area);
    }
  }
}

}  // namespace

EmbeddedSurfaceRule embedded_surface_rule(const Mesh& background, const Mesh& surface, int degree,
                                          const std::vector<char>& active) {
  if (surface.cell != CellType::Triangle || surface.order != 1)
    throw std::invalid_argument("embedded_surface_rule: the surface must be a mesh of linear triangles");
  if (!surface.nodes.allFinite()) throw std::invalid_argument("embedded_surface_rule: a surface node is not finite");
  const int ne = background.num_elements(), nt = surface.num_elements();
  if (!active.empty() && static_cast<int>(active.size()) != ne)
    throw std::invalid_argument(fmt::format("embedded_surface_rule: {} activity flags for {} elements", active.size(), ne));
  const QuadratureRule& ref = quadrature_rule(CellType::Triangle, degree);

  // The triangles: vertices, unit normals, bounding boxes for the bucket grid.
  std::vector<ConvexPolygon> triangles(nt);
  std::vector<Eigen::Vector3d> normals(nt);
  std::vector<double> areas(nt);
  std::vector<Eigen::AlignedBox3d> boxes(nt);
  for (int t = 0; t < nt; ++t) {
    for (int i = 0; i < 3; ++i) {
      triangles[t].push_back(surface.nodes.col(surface.elements(i, t)));
      boxes[t].extend(triangles[t].back());
    }
    const Eigen::Vector3d n2 = (triangles[t][1] - triangles[t][0]).cross(triangles[t][2] - triangles[t][0]);
    areas[t] = 0.5 * n2.norm();
    normals[t] = areas[t] > 0.0 ? Eigen::Vector3d(n2.normalized()) : Eigen::Vector3d::Zero();
  }
  const BoxBucketGrid grid(std::move(boxes));
  std::vector<AffineCell> maps;
  maps.reserve(ne);
  for (int e = 0; e < ne; ++e) maps.push_back(affine_cell(background, e));  // throws before any work

  // Every cell clips the triangles near it; inactive cells too (their points are
  // relocated below), so that no part of the surface is lost.
  std::vector<CellPoints> per_cell(ne);
#pragma omp parallel for schedule(dynamic, 16)
  for (int e = 0; e < ne; ++e) {
    const Eigen::Matrix3Xd vertices =
        background.nodes(Eigen::all, background.elements.col(e).head(background.vertices_per_element()));
    const std::vector<HalfSpace> planes = cell_half_spaces(background.cell, maps[e]);
    for (int t : grid.candidates(vertices.rowwise().minCoeff(), vertices.rowwise().maxCoeff())) {
      if (!(areas[t] > 0.0)) continue;
      ConvexPolygon piece = triangles[t];
      for (const HalfSpace& h : planes) {
        piece = clip_polygon(piece, h, kOnFace);
        if (piece.size() < 3) break;
      }
      if (piece.size() < 3 || belongs_to_neighbour(piece, planes, normals[t])) continue;
      add_piece(piece, normals[t], 1e-14 * areas[t], ref, per_cell[e]);
    }
  }

  EmbeddedSurfaceRule rule;
  size_t n = 0;
  for (const CellPoints& c : per_cell) n += c.weights.size();
  rule.element.reserve(n);
  rule.xi.resize(3, static_cast<Eigen::Index>(n));
  rule.points.resize(3, static_cast<Eigen::Index>(n));
  rule.normals.resize(3, static_cast<Eigen::Index>(n));
  rule.weights.resize(static_cast<Eigen::Index>(n));
  std::vector<int> moved;  // indices of points in inactive cells
  Eigen::Index q = 0;
  for (int e = 0; e < ne; ++e)
    for (size_t k = 0; k < per_cell[e].weights.size(); ++k, ++q) {
      rule.element.push_back(e);
      rule.points.col(q) = per_cell[e].points[k];
      rule.xi.col(q) = maps[e].reference(per_cell[e].points[k]);
      rule.normals.col(q) = per_cell[e].normals[k];
      rule.weights[q] = per_cell[e].weights[k];
      if (!active.empty() && !active[e]) moved.push_back(static_cast<int>(q));
    }
  if (!moved.empty()) {
    const EmbeddedPointMap map = locate_embedded_points(background, rule.points(Eigen::all, moved), active);
    for (size_t k = 0; k < moved.size(); ++k) rule.element[moved[k]] = map.element[k];
    rule.xi(Eigen::all, moved) = map.xi;
    rule.num_relocated = static_cast<int>(moved.size());
  }
  return rule;
}

Eigen::VectorXd surface_load_vector(const Mesh& background, const EmbeddedSurfaceRule& rule,
                                    const SurfaceTraction& traction) {
  const ReferenceBasis& basis = lagrange_basis(background.cell, background.order);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(background.num_nodes()));
  Eigen::VectorXd N(basis.size());
  for (int q = 0; q < rule.size(); ++q) {
    const Eigen::Vector3d t = rule.weights[q] * traction(rule.points.col(q), rule.normals.col(q));
    basis.evaluate(rule.xi.col(q), N);
    for (int i = 0; i < basis.size(); ++i) b.segment<3>(3 * background.elements(i, rule.element[q])) += N[i] * t;
  }
  return b;
}

}  // namespace hofem
