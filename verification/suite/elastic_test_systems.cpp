#include "elastic_test_systems.hpp"

#include "assembly/assembler.hpp"
#include "material/material.hpp"
#include "problem/static_elasticity.hpp"

#include <cmath>
#include <utility>

namespace hofem::verification {

ClampedElasticBody::ClampedElasticBody(Mesh m) : mesh(std::move(m)), dofs(mesh.num_nodes(), mesh.node_set("xmin")) {
  const Assembler a(mesh, dofs);
  const auto mat = make_material("linear", LameParameters::from_young_poisson(1.0, 0.3));
  Eigen::VectorXd g;
  K = a.new_matrix();
  a.hessian(*mat, Eigen::Map<const Eigen::VectorXd>(mesh.nodes.data(), 3 * mesh.num_nodes()), g, K, false);
}

ClampedElasticBody::ClampedElasticBody(CellType cell, int order, int n)
    : ClampedElasticBody(box_mesh(unit_cube(n), cell, order)) {}

Eigen::VectorXd smooth_rhs(Eigen::Index n) {
  Eigen::VectorXd b(n);
  for (Eigen::Index i = 0; i < n; ++i) b[i] = std::sin(0.37 * static_cast<double>(i)) + 0.1;
  return b;
}

Eigen::MatrixXd dense_inverse(const Preconditioner& M, Eigen::Index n) {
  Eigen::MatrixXd Minv(n, n);
  Eigen::VectorXd e = Eigen::VectorXd::Zero(n), z;
  for (Eigen::Index i = 0; i < n; ++i) {
    e[i] = 1.0;
    M.apply(e, z);
    Minv.col(i) = z;
    e[i] = 0.0;
  }
  return Minv;
}

PulledBodySolve solve_pulled_neohookean(const Mesh& mesh, const std::string& linear_solver) {
  const auto mat = make_material("neohookean", LameParameters::from_young_poisson(1.0, 0.3));
  VectorField pull = [](const Eigen::Vector3d& X) { return Eigen::Vector3d(0.1 * X[0], 0.05 * X[1] * X[0], 0.0); };
  StaticOptions opt;
  opt.solver = SolverSpec::parse(linear_solver);
  opt.newton.rtol = 1e-10;
  StaticElasticity p(mesh, *mat, {{mesh.node_set("xmin"), nullptr}, {mesh.node_set("xmax"), pull}}, nullptr, opt);
  const StaticReport r = p.solve();
  return {r.converged, r.message, p.displacement()};
}

}  // namespace hofem::verification
