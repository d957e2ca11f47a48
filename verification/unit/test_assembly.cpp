// Assembly, Newton and the static problem: behaviour the verification rows do
// not pin down (reproducibility across thread counts, Dirichlet elimination,
// load stepping, error reporting).
#include "assembly/assembler.hpp"
#include "material/material.hpp"
#include "mesh/box_mesh.hpp"
#include "mesh/mesh_upgrade.hpp"
#include "problem/static_elasticity.hpp"

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>
#include <omp.h>

namespace hofem {
namespace {

Eigen::VectorXd deformed(const Mesh& m, double a) {
  Eigen::VectorXd x(3 * m.num_nodes());
  for (int n = 0; n < m.num_nodes(); ++n) {
    const Eigen::Vector3d X = m.nodes.col(n);
    x.segment<3>(3 * n) = X + a * Eigen::Vector3d(std::sin(2 * X[1]), X[0] * X[2], X[0] * X[0]);
  }
  return x;
}

// Elements of one colour share no node, and colours run in a fixed order, so
// the assembled values are bitwise identical for any thread count.
TEST(Assembler, BitwiseReproducibleAcrossThreadCounts) {
  const Mesh m = box_mesh(unit_cube(6), CellType::Tetrahedron, 2);  // > 512 elements: parallel path
  const DofMap dofs(m.num_nodes(), m.node_set("xmin"));
  const Assembler a(m, dofs);
  const auto mat = make_material("neohookean", LameParameters::from_young_poisson(1.0, 0.3));
  const Eigen::VectorXd x = deformed(m, 0.05);
  const int previous = omp_get_max_threads();
  Eigen::VectorXd g1, g2;
  SparseMatrix K1 = a.new_matrix(), K2 = a.new_matrix();
  omp_set_num_threads(1);
  const double e1 = a.hessian(*mat, x, g1, K1, false);
  omp_set_num_threads(2);
  const double e2 = a.hessian(*mat, x, g2, K2, false);
  omp_set_num_threads(previous);
  EXPECT_EQ(e1, e2);
  EXPECT_EQ((g1 - g2).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(Eigen::Map<const Eigen::VectorXd>(K1.valuePtr(), K1.nonZeros()),
            Eigen::Map<const Eigen::VectorXd>(K2.valuePtr(), K2.nonZeros()));
}

TEST(Assembler, PatternHasFreeDofsOnlyAndIsSymmetric) {
  const Mesh m = box_mesh(unit_cube(2), CellType::Hexahedron, 2);
  const DofMap dofs(m.num_nodes(), m.node_set("boundary"));
  const Assembler a(m, dofs);
  EXPECT_EQ(a.new_matrix().rows(), dofs.num_free());
  const auto mat = make_material("stvk", LameParameters::from_young_poisson(1.0, 0.3));
  Eigen::VectorXd g;
  SparseMatrix K = a.new_matrix();
  a.hessian(*mat, deformed(m, 0.03), g, K, false);
  const Eigen::MatrixXd D(K);
  EXPECT_LE((D - D.transpose()).cwiseAbs().maxCoeff(), 1e-14 * D.cwiseAbs().maxCoeff());
  EXPECT_THROW(a.energy(*mat, Eigen::VectorXd::Zero(5)), std::invalid_argument);
}

TEST(Assembler, InvertedDeformationReportsTheElement) {
  const Mesh m = box_mesh(unit_cube(2), CellType::Tetrahedron, 1);
  const DofMap dofs(m.num_nodes(), {});
  const Assembler a(m, dofs);
  const auto nh = make_material("neohookean", LameParameters::from_young_poisson(1.0, 0.3));
  Eigen::VectorXd x = deformed(m, 0.0);
  x.segment<3>(3 * m.elements(3, 7)) = x.segment<3>(3 * m.elements(0, 7)) + Eigen::Vector3d(-0.3, -0.3, -0.3);
  EXPECT_TRUE(std::isinf(a.energy(*nh, x)));  // energy: +inf so a line search backs off
  Eigen::VectorXd g;
  try {
    a.gradient(*nh, x, g);
    FAIL() << "no error for an inverted element";
  } catch (const MaterialDomainError& e) {
    EXPECT_NE(std::string(e.what()).find("element "), std::string::npos) << e.what();
  }
  const auto snh = make_material("stable-neohookean", LameParameters::from_young_poisson(1.0, 0.3));
  EXPECT_TRUE(std::isfinite(a.gradient(*snh, x, g)));  // Stable Neo-Hookean is defined when inverted
}

// Compressing a 3-long bar by 0.6 (20 %, below its buckling strain) in one step pushes the last layer of elements
// (0.5 long) through itself: without the predictor the first Newton iterate is
// inverted and the solver must fall back to smaller load steps; with it, the
// linearised step lands on a valid state and no extra steps are needed.
TEST(StaticElasticity, LoadSteppingRecoversWhereAFullStepInverts) {
  const Mesh m = box_mesh(BoxSpec{{0, 0, 0}, {3, 1, 1}, {6, 2, 2}}, CellType::Tetrahedron, 2);
  const auto mat = make_material("neohookean", LameParameters::from_young_poisson(1.0, 0.3));
  VectorField push = [](const Eigen::Vector3d&) { return Eigen::Vector3d(-0.6, 0.0, 0.0); };
  for (bool predictor : {false, true}) {
    StaticOptions opt;
    opt.predictor = predictor;
    opt.solver = SolverSpec::parse("cholmod");  // the symbolic-analysis count below is a direct solver's
    StaticElasticity p(m, *mat, {{m.node_set("xmin"), nullptr}, {m.node_set("xmax"), push}}, nullptr, opt);
    const StaticReport r = p.solve();
    EXPECT_TRUE(r.converged) << r.message;
    if (!predictor) {
      EXPECT_GT(r.load_steps, 1) << "a full step should have failed";
    }
    EXPECT_EQ(r.symbolic_analyses, 1);  // one symbolic factorisation for the whole solve
    for (const auto& step : r.steps)
      if (step.converged) {
        EXPECT_LE(step.final_residual, 1e-9 * step.force_scale);
      }
    const int corner = m.node_set("xmax").front();
    EXPECT_EQ(p.displacement().segment<3>(3 * corner), push(m.nodes.col(corner)));  // prescribed exactly
  }
}

// A nodal external load adds to the integrated body force: linear elasticity
// superposes, u(b + g) = u(b) + u(g). Three CHOLMOD solves of a linear problem
// (one Newton step each, residual at round-off); measured |u(b+g) - u(b) - u(g)|
// / |u(b+g)| ~1e-15, so 1e-10 is round-off with a wide margin, while a load that
// replaced the body force instead of adding to it misses u(b): O(1) here (the
// two loads are of one size).
TEST(StaticElasticity, ExternalLoadAddsToTheBodyForce) {
  const Mesh m = box_mesh(unit_cube(2), CellType::Tetrahedron, 2);
  const auto mat = make_material("linear", LameParameters::from_young_poisson(1.0, 0.3));
  const VectorField gravity = [](const Eigen::Vector3d&) { return Eigen::Vector3d(0.0, 0.0, -0.1); };
  Eigen::VectorXd pull = Eigen::VectorXd::Zero(3 * m.num_nodes());
  for (int n : m.node_set("xmax")) pull[3 * n] = 0.01;
  auto solve = [&](const VectorField& body, const Eigen::VectorXd& nodal) {
    StaticOptions opt;
    opt.solver = SolverSpec::parse("cholmod");
    opt.external_load = nodal;
    StaticElasticity p(m, *mat, {{m.node_set("xmin"), nullptr}}, body, opt);
    const StaticReport r = p.solve();
    EXPECT_TRUE(r.converged) << r.message;
    return Eigen::VectorXd(p.displacement());
  };
  const Eigen::VectorXd both = solve(gravity, pull), body = solve(gravity, Eigen::VectorXd()),
                        nodal = solve(nullptr, pull);
  ASSERT_GT(body.norm(), 0.1 * both.norm());  // both loads matter, or the check proves nothing
  ASSERT_GT(nodal.norm(), 0.1 * both.norm());
  EXPECT_LE((both - body - nodal).norm() / both.norm(), 1e-10);
}

TEST(StaticElasticity, RejectsInvertedInputMeshWithTheElementIndex) {
  Mesh m = box_mesh(unit_cube(2), CellType::Tetrahedron, 1);
  std::swap(m.elements(1, 4), m.elements(2, 4));
  const auto mat = make_material("linear", LameParameters::from_young_poisson(1.0, 0.3));
  try {
    StaticElasticity p(m, *mat, {{m.node_set("boundary"), nullptr}}, nullptr, {});
    FAIL();
  } catch (const MeshError& e) {
    EXPECT_NE(std::string(e.what()).find("element 4: inverted"), std::string::npos) << e.what();
  }
  // A solver is a SolverSpec, parsed (and refused) before any problem sees it.
  EXPECT_THROW(SolverSpec::parse("magic"), std::invalid_argument);
}

// The consistent mass matrix of any order integrates rho over the body exactly.
// min det F per element: 1 at rest, 8 under x = 2 X, -1 under a mirror
// (x = -X, Y, Z) that inverts every element; for these affine maps F is the
// same at every quadrature point, so the values are exact up to round-off in
// J^-1 (1e-12 relative is 1e4 eps, well above it).
TEST(Assembler, ElementMinDetFSeesVolumeChangeAndInversion) {
  const Mesh mesh = box_mesh(unit_cube(2), CellType::Tetrahedron, 2);
  const DofMap dofs(mesh.num_nodes(), {});
  const Assembler a(mesh, dofs);
  const Eigen::VectorXd X = Eigen::Map<const Eigen::VectorXd>(mesh.nodes.data(), 3 * mesh.num_nodes());
  Eigen::VectorXd mirrored = X;
  for (int i = 0; i < mesh.num_nodes(); ++i) mirrored[3 * i] = -X[3 * i];
  const Eigen::VectorXd at_rest = a.element_min_det_F(X), doubled = a.element_min_det_F(2.0 * X),
                        inverted = a.element_min_det_F(mirrored);
  ASSERT_EQ(at_rest.size(), mesh.num_elements());
  EXPECT_LE((at_rest.array() - 1.0).abs().maxCoeff(), 1e-12);
  EXPECT_LE((doubled.array() - 8.0).abs().maxCoeff(), 8e-12);
  EXPECT_LE((inverted.array() + 1.0).abs().maxCoeff(), 1e-12);
}

TEST(Assembler, ConsistentMassMatrixTotalMass) {
  for (int p = 1; p <= 4; ++p) {
    const Mesh m = box_mesh(BoxSpec{{0, 0, 0}, {2, 1, 1}, {2, 1, 1}}, CellType::Tetrahedron, p);
    const DofMap dofs(m.num_nodes(), {});
    const Assembler a(m, dofs);
    const SparseMatrix M = a.mass_matrix(3.0, 2 * p);
    EXPECT_NEAR(M.sum() / 3.0, 3.0 * 2.0, 1e-12) << "order " << p;
    const Eigen::MatrixXd D(M);
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(D).eigenvalues().minCoeff(), 0.0) << "order " << p;
  }
}

}  // namespace
}  // namespace hofem
