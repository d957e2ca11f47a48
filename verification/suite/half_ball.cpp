#include "half_ball.hpp"

#include "embedded/embedded_points.hpp"
#include "mesh/box_mesh.hpp"

#include <algorithm>
#include <vector>

namespace hofem::verification {

Mesh half_ball(int k) {
  Mesh m = box_mesh(BoxSpec{{-1, -1, 0}, {1, 1, 1}, {2 * k, 2 * k, k}}, CellType::Tetrahedron, 1);
  for (int n = 0; n < m.num_nodes(); ++n) {
    const Eigen::Vector3d X = m.nodes.col(n);
    const double r = X.norm();
    const Eigen::Vector3d Y = r > 0.0 ? Eigen::Vector3d(X * (X.cwiseAbs().maxCoeff() / r)) : X;
    m.nodes.col(n) = 0.5 * Y + Eigen::Vector3d(0.5, 0.5, 0.0);
  }
  return m;
}

Mesh half_ball_curved_surface(const Mesh& half_ball) {
  const Mesh surface = boundary_surface(half_ball);
  std::vector<int> keep;
  for (int t = 0; t < surface.num_elements(); ++t) {
    double top = 0.0;
    for (int i = 0; i < 3; ++i) top = std::max(top, surface.nodes(2, surface.elements(i, t)));
    if (top > 1e-12) keep.push_back(t);  // not all three vertices on z = 0
  }
  Mesh curved = surface;
  curved.elements.resize(3, static_cast<Eigen::Index>(keep.size()));
  for (size_t k = 0; k < keep.size(); ++k) curved.elements.col(static_cast<Eigen::Index>(k)) = surface.elements.col(keep[k]);
  return curved;
}

}  // namespace hofem::verification
