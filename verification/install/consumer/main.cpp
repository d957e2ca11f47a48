// The installed hofem in use, as another project would use it:
//  1. the volume of the unit cube, meshed by hofem's box mesher (2 x 2 x 2 cubes
//     split into tetrahedra) and integrated by a quadrature rule from its library,
//     element by element: sum_e |det J_e| * sum_q w_q (exact value 1);
//  2. a whole simulation through the core's public API: the manufactured-solution
//     problem (linear elasticity, Tet10, CHOLMOD) on n = 4 and n = 8, and the
//     observed L2 rate between them (asymptotically p + 1 = 3). This pulls in
//     every layer below study/ and the libraries they link (SuiteSparse, OpenBLAS,
//     OpenMP, MPI and hypre at start-up), so an install that lists a dependency
//     wrongly fails here at link or run time.
// ctest install.consumer checks both printed numbers.
#include "mesh/box_mesh.hpp"
#include "quadrature/rule_library.hpp"
#include "solver/solver_spec.hpp"
#include "study/manufactured_solution.hpp"

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

  double l2[2] = {0.0, 0.0};
  const int sizes[2] = {4, 8};
  for (int k = 0; k < 2; ++k) {
    hofem::MmsCase c;
    c.problem = "linear";
    c.order = 2;
    c.n = sizes[k];
    c.solver = hofem::SolverSpec::parse("cholmod");
    const hofem::MmsResult r = hofem::run_mms(c);
    if (!r.converged) {
      std::printf("hofem consumer: manufactured solution n = %d did not converge: %s\n", c.n, r.message.c_str());
      return 1;
    }
    l2[k] = r.l2_error;
    std::printf("hofem consumer: manufactured solution, Tet10, n = %d: %d unknowns, %s, L2 error %.6g\n", c.n,
                r.dofs, r.linear_solver.c_str(), r.l2_error);
  }
  std::printf("hofem consumer: observed L2 rate %.4f\n", std::log2(l2[0] / l2[1]));
  return 0;
}
