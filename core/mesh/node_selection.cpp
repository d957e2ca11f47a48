#include "mesh/node_selection.hpp"

namespace hofem {

std::vector<int> nodes_in_box(const Mesh& mesh, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  const double tol = 1e-9 * (mesh.nodes.rowwise().maxCoeff() - mesh.nodes.rowwise().minCoeff()).norm();
  std::vector<int> nodes;
  for (int i = 0; i < mesh.num_nodes(); ++i)
    if ((mesh.nodes.col(i).array() >= lo.array() - tol).all() && (mesh.nodes.col(i).array() <= hi.array() + tol).all())
      nodes.push_back(i);
  return nodes;
}

}  // namespace hofem
