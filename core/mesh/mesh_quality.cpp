#include "mesh/mesh_quality.hpp"

#include "basis/basis_tabulation.hpp"
#include "basis/reference_basis.hpp"
#include "quadrature/rule_library.hpp"

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace hofem {

namespace {

// Dihedral angles (degrees) of the tetrahedron with vertices a, b, c, d: the
// angle at each edge between the two faces that share it, from the face normals.
void dihedral_range(const Eigen::Vector3d v[4], double& lo, double& hi) {
  const int edges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  for (const auto& e : edges) {
    int o[2], k = 0;
    for (int i = 0; i < 4; ++i)
      if (i != e[0] && i != e[1]) o[k++] = i;
    const Eigen::Vector3d axis = v[e[1]] - v[e[0]];
    const Eigen::Vector3d n1 = axis.cross(v[o[0]] - v[e[0]]), n2 = axis.cross(v[o[1]] - v[e[0]]);
    const double c = n1.dot(n2) / (n1.norm() * n2.norm());
    const double angle = std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / M_PI;
    lo = std::min(lo, angle);
    hi = std::max(hi, angle);
  }
}

}  // namespace

ElementJacobians::ElementJacobians(CellType cell, int order) {
  const ReferenceBasis& basis = lagrange_basis(cell, order);
  const BasisTabulation& tab = cached_tabulation(cell, order, 2 * order);
  for (int p = 0; p < tab.num_points; ++p) point_gradients_.emplace_back(tab.gradient(p));
  quadrature_points_ = tab.num_points;
  const Eigen::MatrixXd verts = reference_vertices(cell);
  for (int v = 0; v < verts.cols(); ++v) point_gradients_.push_back(basis.gradients(verts.col(v)));
}

ElementJacobians::Extremes ElementJacobians::extremes(const Mesh& mesh, int element) const {
  Eigen::Matrix3Xd X(3, mesh.nodes_per_element());
  for (int i = 0; i < mesh.nodes_per_element(); ++i) X.col(i) = mesh.nodes.col(mesh.elements(i, element));
  Extremes d{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(), "", 0};
  for (std::size_t k = 0; k < point_gradients_.size(); ++k) {
    const double det = (X * point_gradients_[k]).determinant();
    const int q = static_cast<int>(k);
    // A NaN (overflowing coordinates) is kept as the minimum: it must not pass for valid.
    if (!(det >= d.min) && !std::isnan(d.min)) {
      d.min = det;
      d.where = q < quadrature_points_ ? "quadrature point" : "vertex";
      d.index = q < quadrature_points_ ? q : q - quadrature_points_;
    }
    d.max = std::max(d.max, det);
  }
  return d;
}

MeshQuality measure_quality(const Mesh& mesh, int quadrature_degree) {
  const int degree = quadrature_degree >= 0 ? quadrature_degree : 2 * mesh.order;
  const BasisTabulation& tab = cached_tabulation(mesh.cell, mesh.order, degree);
  MeshQuality q;
  q.min_dihedral_degrees = mesh.cell == CellType::Tetrahedron ? 180.0 : 0.0;
  q.max_dihedral_degrees = 0.0;
  q.min_jacobian_ratio = std::numeric_limits<double>::infinity();
  Eigen::Matrix3Xd X(3, mesh.nodes_per_element());
  for (int e = 0; e < mesh.num_elements(); ++e) {
    for (int i = 0; i < mesh.nodes_per_element(); ++i) X.col(i) = mesh.nodes.col(mesh.elements(i, e));
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (int p = 0; p < tab.num_points; ++p) {
      const double det = (X * tab.gradient(p)).determinant();
      lo = std::min(lo, det);
      hi = std::max(hi, det);
    }
    const double ratio = hi > 0 ? lo / hi : -1.0;
    if (lo <= 0.0) ++q.inverted_elements;
    if (ratio < q.min_jacobian_ratio) q.min_jacobian_ratio = ratio, q.worst_element = e;
    if (mesh.cell == CellType::Tetrahedron) {
      const Eigen::Vector3d v[4] = {X.col(0), X.col(1), X.col(2), X.col(3)};
      dihedral_range(v, q.min_dihedral_degrees, q.max_dihedral_degrees);
    }
  }
  return q;
}

void validate_mesh(const Mesh& mesh) {
  if (mesh.cell != CellType::Tetrahedron && mesh.cell != CellType::Hexahedron)
    throw MeshError(fmt::format("mesh of {} cells: only tetrahedra and hexahedra are supported", name(mesh.cell)));
  if (mesh.nodes_per_element() != nodes_per_element(mesh.cell, mesh.order))
    throw MeshError(fmt::format("mesh has {} nodes per element, order {} {} needs {}", mesh.nodes_per_element(),
                                mesh.order, name(mesh.cell), nodes_per_element(mesh.cell, mesh.order)));
  if (mesh.num_elements() == 0) throw MeshError("mesh has no elements");
  if (!mesh.nodes.allFinite()) throw MeshError("mesh has non-finite node coordinates");
  for (int e = 0; e < mesh.num_elements(); ++e)
    for (int i = 0; i < mesh.nodes_per_element(); ++i)
      if (mesh.elements(i, e) < 0 || mesh.elements(i, e) >= mesh.num_nodes())
        throw MeshError(fmt::format("{}: node index {} out of range [0, {})", describe_element(mesh, e),
                                    mesh.elements(i, e), mesh.num_nodes()));
  // Typical element volume scale: bounding box volume / number of elements.
  const Eigen::Vector3d ext = mesh.nodes.rowwise().maxCoeff() - mesh.nodes.rowwise().minCoeff();
  const double scale = std::max(ext.prod(), std::pow(ext.maxCoeff(), 3) * 1e-30) / mesh.num_elements();
  const ElementJacobians jacobians(mesh.cell, mesh.order);
  for (int e = 0; e < mesh.num_elements(); ++e) {
    const ElementJacobians::Extremes d = jacobians.extremes(mesh, e);
    const double tiny = 1e-12 * scale / reference_volume(mesh.cell);  // det J of a flat element, rounding included
    const bool flat = std::abs(d.min) <= tiny && std::abs(d.max) <= tiny;
    if (!flat && !(d.min > 0.0)) {
      // Negative everywhere: the nodes are numbered the wrong way round, which a
      // renumbering (or --reorient, for straight elements) fixes. Mixed signs: the
      // element folds (a mid-edge node pushed out, a twisted hex): fix the geometry.
      const bool everywhere = d.max < 0.0;
      throw MeshError(fmt::format(
          "{}: inverted (det J = {:.3e} at {} {}{}); {}", describe_element(mesh, e), d.min, d.where, d.index,
          everywhere ? ", negative at every point" : fmt::format(", {:.3e} elsewhere", d.max),
          everywhere ? "its nodes are ordered the wrong way round: renumber them in the mesh generator, or run with "
                       "--reorient to flip straight inverted elements"
                     : "the element folds over itself (a mid-edge node pushed out, a twisted hex): move its nodes"));
    }
    if (flat || d.min < tiny)
      throw MeshError(fmt::format("{}: degenerate (det J = {:.3e} at {} {}, typical element volume {:.3e}): flat, "
                                  "coplanar or repeated nodes; remove or repair the element",
                                  describe_element(mesh, e), d.min, d.where, d.index, scale));
  }
}

}  // namespace hofem
