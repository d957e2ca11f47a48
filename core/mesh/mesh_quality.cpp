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
        throw MeshError(fmt::format("element {}: node index {} out of range [0, {})", e, mesh.elements(i, e), mesh.num_nodes()));
  // Typical element volume scale: bounding box volume / number of elements.
  const Eigen::Vector3d ext = mesh.nodes.rowwise().maxCoeff() - mesh.nodes.rowwise().minCoeff();
  const double scale = std::max(ext.prod(), std::pow(ext.maxCoeff(), 3) * 1e-30) / mesh.num_elements();
  // Quadrature points of the stiffness rule plus the vertices (a curved element
  // can be valid at its quadrature points and fold at a corner).
  const ReferenceBasis& basis = lagrange_basis(mesh.cell, mesh.order);
  const BasisTabulation& tab = cached_tabulation(mesh.cell, mesh.order, 2 * mesh.order);
  std::vector<Eigen::MatrixXd> vertex_grads;
  const Eigen::MatrixXd verts = reference_vertices(mesh.cell);
  for (int v = 0; v < verts.cols(); ++v) vertex_grads.push_back(basis.gradients(verts.col(v)));
  Eigen::Matrix3Xd X(3, mesh.nodes_per_element());
  for (int e = 0; e < mesh.num_elements(); ++e) {
    for (int i = 0; i < mesh.nodes_per_element(); ++i) X.col(i) = mesh.nodes.col(mesh.elements(i, e));
    auto check = [&](double det, const char* where, int k) {
      if (det <= 0.0)
        throw MeshError(fmt::format("element {}: inverted (det J = {:.3e} at {} {})", e, det, where, k));
      if (det * reference_volume(mesh.cell) < 1e-12 * scale)
        throw MeshError(fmt::format("element {}: degenerate (det J = {:.3e} at {} {}, typical element volume {:.3e})", e, det,
                                    where, k, scale));
    };
    for (int p = 0; p < tab.num_points; ++p) check((X * tab.gradient(p)).determinant(), "quadrature point", p);
    for (size_t v = 0; v < vertex_grads.size(); ++v) check((X * vertex_grads[v]).determinant(), "vertex", static_cast<int>(v));
  }
}

}  // namespace hofem
