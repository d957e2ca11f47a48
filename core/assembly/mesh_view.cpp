#include "assembly/mesh_view.hpp"

#include <Eigen/Geometry>

namespace hofem {

Eigen::MatrixXd rigid_rotations(const MeshView& d, const Eigen::Vector3d* given_centre) {
  const Eigen::Vector3d centre = given_centre ? *given_centre : Eigen::Vector3d(d.mesh->nodes.rowwise().mean());
  const std::vector<int>& free = d.dofs->free_dofs();
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(free.size()), 3);
  for (size_t i = 0; i < free.size(); ++i) {
    const int node = free[i] / 3, c = free[i] % 3;
    const Eigen::Vector3d X = d.mesh->nodes.col(node) - centre;
    for (int k = 0; k < 3; ++k) R(static_cast<Eigen::Index>(i), k) = Eigen::Vector3d::Unit(k).cross(X)[c];
  }
  return R;
}

}  // namespace hofem
