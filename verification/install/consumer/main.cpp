// The installed hofem in use: the volume of the unit cube, meshed by hofem's box
// mesher (2 x 2 x 2 cubes split into tetrahedra) and integrated by a quadrature rule
// from its library, element by element: sum_e |det J_e| * sum_q w_q. The exact
// value is 1; ctest install.consumer checks the printed number against it.
#include "mesh/box_mesh.hpp"
#include "quadrature/rule_library.hpp"

#include <Eigen/Dense>

#include <cmath>
#include <cstdio>

int main() {
  const hofem::Mesh mesh = hofem::box_tet_mesh(hofem::unit_cube(2));
  // Degree 2 rather than 0: a rule with several points and weights, not one weight.
  const hofem::QuadratureRule& rule = hofem::quadrature_rule(hofem::CellType::Tetrahedron, 2);
  double volume = 0.0;
  for (int e = 0; e < mesh.num_elements(); ++e) {
    const Eigen::Vector3d x0 = mesh.nodes.col(mesh.elements(0, e));
    Eigen::Matrix3d jacobian;
    for (int k = 1; k <= 3; ++k) jacobian.col(k - 1) = mesh.nodes.col(mesh.elements(k, e)) - x0;
    volume += std::abs(jacobian.determinant()) * rule.weights.sum();
  }
  std::printf("hofem consumer: %d tetrahedra, rule %s (%d points), unit cube volume %.17g\n",
              mesh.num_elements(), rule.id.c_str(), rule.size(), volume);
  return 0;
}
