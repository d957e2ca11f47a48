#include "mesh/mesh_reorient.hpp"

#include "basis/reference_basis.hpp"
#include "mesh/mesh_quality.hpp"

#include <fmt/format.h>

#include <cmath>

namespace hofem {

namespace {

// perm[i] = the node whose reference position is node i's with x and y swapped.
std::vector<int> mirror_permutation(const ReferenceBasis& basis) {
  const Eigen::MatrixXd& ref = basis.nodes();
  std::vector<int> perm(static_cast<std::size_t>(basis.size()), -1);
  for (int i = 0; i < basis.size(); ++i) {
    Eigen::Vector3d mirrored(ref(1, i), ref(0, i), ref(2, i));
    for (int j = 0; j < basis.size(); ++j)
      if ((ref.col(j) - mirrored).norm() < 1e-12) perm[static_cast<std::size_t>(i)] = j;
    if (perm[static_cast<std::size_t>(i)] < 0)
      throw std::logic_error(fmt::format("{}: node {} has no mirror image", basis.element_name(), i));
  }
  return perm;
}

// True when every node is where the vertices' (bi/tri)linear map puts its
// reference position, to 1e-9 of the element's size (rounding in a file's
// printed coordinates is far below that, a curved mid-edge node far above).
bool is_straight(const Mesh& mesh, int e, const ReferenceBasis& basis, const ReferenceBasis& vertex_basis) {
  const int nv = vertex_basis.size();
  Eigen::Matrix3Xd V(3, nv);
  for (int v = 0; v < nv; ++v) V.col(v) = mesh.nodes.col(mesh.elements(v, e));
  const double size = (V.rowwise().maxCoeff() - V.rowwise().minCoeff()).norm();
  for (int i = nv; i < basis.size(); ++i) {
    const Eigen::Vector3d linear = V * vertex_basis.evaluate(basis.nodes().col(i));
    if ((mesh.nodes.col(mesh.elements(i, e)) - linear).norm() > 1e-9 * size) return false;
  }
  return true;
}

}  // namespace

std::vector<int> reorient_inverted_elements(Mesh& mesh) {
  const ReferenceBasis& basis = lagrange_basis(mesh.cell, mesh.order);
  const ReferenceBasis& vertex_basis = lagrange_basis(mesh.cell, 1);
  const std::vector<int> perm = mirror_permutation(basis);
  const ElementJacobians jacobians(mesh.cell, mesh.order);
  std::vector<int> flipped;
  Eigen::VectorXi old(mesh.nodes_per_element());
  for (int e = 0; e < mesh.num_elements(); ++e) {
    const ElementJacobians::Extremes d = jacobians.extremes(mesh, e);
    if (!(d.max < 0.0) || !is_straight(mesh, e, basis, vertex_basis)) continue;
    old = mesh.elements.col(e);
    for (int i = 0; i < mesh.nodes_per_element(); ++i) mesh.elements(i, e) = old[perm[static_cast<std::size_t>(i)]];
    flipped.push_back(e);
  }
  return flipped;
}

}  // namespace hofem
