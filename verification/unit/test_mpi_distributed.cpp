// Distributed assembly into hypre and its solve (issue 7), run by ctest on one
// rank (hofem_mpi_tests) and on two (mpi.two_ranks: mpirun -np 2): either way
// the answer must be the serial one.
#include "assembly/assembler.hpp"
#include "assembly/distributed_dofs.hpp"
#include "dynamics/dynamic_elasticity.hpp"
#include "material/material.hpp"
#include "mesh/box_mesh.hpp"
#include "mesh/mesh_partition.hpp"
#include "parallel/mpi_runtime.hpp"
#include "solver/distributed_system.hpp"
#include "solver/linear_solver.hpp"
#include "manufactured_solution.hpp"

#include <fmt/format.h>

#include <gtest/gtest.h>
#include <mpi.h>

namespace hofem {
namespace {

// Linear elasticity on a P2 cube clamped at x = 0 under gravity. Each rank
// assembles only its own elements; hypre sums the shares. The distributed
// AMG-PCG solution equals the serial CHOLMOD one to 1e-9 relative: PCG stops at
// ||r|| <= 1e-12 ||b||, and the error is at most cond(K) (~1e3 here) times that.
TEST(DistributedSystem, EqualsTheSerialSolve) {
  ensure_hypre();
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  const Mesh mesh = box_mesh(BoxSpec{{0, 0, 0}, {2, 1, 1}, {6, 3, 3}}, CellType::Tetrahedron, 2);
  const DofMap dofs(mesh.num_nodes(), mesh.node_set("xmin"));
  const auto material = make_material("linear", LameParameters::from_young_poisson(1e3, 0.3));
  const Eigen::VectorXd X = Eigen::Map<const Eigen::VectorXd>(mesh.nodes.data(), 3 * mesh.num_nodes());
  auto gravity = [](const Eigen::Vector3d&) { return Eigen::Vector3d(0, 0, -9.81); };

  const Assembler serial(mesh, dofs);
  SparseMatrix K = serial.new_matrix();
  Eigen::VectorXd g;
  serial.hessian(*material, X, g, K, false);
  const Eigen::VectorXd b = dofs.restrict(serial.body_force_vector(gravity, 4));
  auto direct = make_linear_solver("cholmod");
  ASSERT_TRUE(direct->factorize(K));
  Eigen::VectorXd reference;
  direct->solve(b, reference);

  const std::vector<int> part = partition_elements(mesh, size);
  Assembler local(mesh, dofs);
  local.set_element_rules(rules_of_part(mesh, part, rank));
  SparseMatrix K_local = local.new_matrix();
  local.hessian(*material, X, g, K_local, false);
  const Eigen::VectorXd b_local = dofs.restrict(local.body_force_vector(gravity, 4));

  DistributedLinearSystem system(MPI_COMM_WORLD, distribute_dofs(mesh, dofs, part, size), dofs);
  Eigen::VectorXd x;
  const DistributedSolveResult r = system.assemble_and_solve(K_local, b_local, x, 1e-12);
  EXPECT_TRUE(r.converged) << r.message;
  EXPECT_LE((x - reference).norm(), 1e-9 * reference.norm()) << "rank " << rank << " of " << size;
  // The ranks' rows together hold the serial matrix: every non-zero entry once
  // (entries summing to exactly zero across ranks may be stored as well).
  long long stored = system.local_nonzeros(), total = 0;
  MPI_Allreduce(&stored, &total, 1, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  long long nonzero = 0;
  for (Eigen::Index q = 0; q < K.nonZeros(); ++q) nonzero += K.valuePtr()[q] != 0.0;
  EXPECT_GE(total, nonzero);
  EXPECT_LE(total, K.nonZeros());
  if (size > 1) EXPECT_LT(system.rows().owned_rows(rank), dofs.num_free());  // really distributed
}

// The manufactured-solution cube (issue 7's verification): the distributed
// static solve (elements over the ranks, hypre AMG-PCG) gives the serial
// (CHOLMOD) L2 and H1 errors to 1e-10 relative, with the same Newton
// iterations. The distributed linear solves stop at 1e-12 (MmsProblem), so the
// tangent predictor and every Newton step match the direct ones to ~1e-12 of
// the step, and Newton's quadratic convergence makes the final iterates agree
// far below the 1e-10 Newton tolerance; measured differences: 0 - 8e-15 on one
// and two ranks. An assembly or numbering fault changes the errors at O(1).
TEST(DistributedSystem, ManufacturedSolutionMatchesSerial) {
  ensure_hypre();
  for (const char* problem : {"linear", "neohookean"})
    for (int order : {1, 2, 3}) {
      verification::MmsCase c;
      c.problem = problem;
      c.order = order;
      c.n = 3;  // 8 / 125 / 512 interior nodes for P1 / P2 / P3
      const verification::MmsResult serial = verification::run_mms(c);
      c.distributed = true;
      const verification::MmsResult distributed = verification::run_mms(c);
      const std::string what = fmt::format("{} P{}", problem, order);
      ASSERT_TRUE(serial.converged && distributed.converged) << what << ": " << distributed.message;
      EXPECT_EQ(distributed.newton_iterations, serial.newton_iterations) << what;
      EXPECT_NEAR(distributed.l2_error / serial.l2_error, 1.0, 1e-10) << what;
      EXPECT_NEAR(distributed.h1_error / serial.h1_error, 1.0, 1e-10) << what;
      RecordProperty(what + " l2 relative difference", fmt::format("{:.3g}", std::abs(distributed.l2_error / serial.l2_error - 1.0)));
    }
}

// Issue 7: the implicit integrator runs unchanged on top of the distributed
// path. A Neo-Hookean P2 beam clamped at x = 0 sags under gravity for 10 implicit
// Euler steps (consistent mass): the distributed trajectory (elastic terms over
// the ranks, hypre AMG-PCG at 1e-12) follows the serial CHOLMOD one with the same
// Newton iterations per step. Both stop Newton at the same relative tolerance
// (1e-9 of the force scale), so positions may differ by that times the
// compliance: 1e-9 of the displacement (measured 1.1e-15 on one and two ranks).
TEST(DistributedSystem, ImplicitEulerTrajectoryMatchesSerial) {
  ensure_hypre();
  const Mesh mesh = box_mesh(BoxSpec{{0, 0, 0}, {3, 1, 1}, {6, 2, 2}}, CellType::Tetrahedron, 2);
  const auto material = make_material("neohookean", LameParameters::from_young_poisson(2e5, 0.35));
  auto run = [&](bool distributed, std::vector<int>& newton) {
    DynamicsOptions o;
    o.integrator = Integrator::ImplicitEuler;
    o.dt = 0.02;
    o.gravity = Eigen::Vector3d(0, 0, -9.81);
    o.distributed = distributed;
    o.newton.linear_rtol = 1e-12;
    DynamicElasticity body(mesh, *material, {PrescribedMotion{mesh.node_set("xmin"), {}, {}, {}}}, o);
    for (int k = 0; k < 10; ++k) {
      const StepReport r = body.step();
      EXPECT_TRUE(r.ok) << r.message;
      newton.push_back(r.newton_iterations);
    }
    return Eigen::VectorXd(body.displacement());
  };
  std::vector<int> newton_serial, newton_distributed;
  const Eigen::VectorXd serial = run(false, newton_serial);
  const Eigen::VectorXd distributed = run(true, newton_distributed);
  EXPECT_EQ(newton_distributed, newton_serial);
  const double difference = (distributed - serial).norm() / serial.norm();
  EXPECT_LE(difference, 1e-9) << "relative trajectory difference " << difference;
  EXPECT_GT(serial.cwiseAbs().maxCoeff(), 1e-3);  // it really moved
  RecordProperty("relative trajectory difference", fmt::format("{:.3g}", difference));
}

TEST(DistributedSystem, RefusesANumberingForAnotherRankCount) {
  ensure_hypre();
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  const Mesh mesh = box_mesh(unit_cube(2), CellType::Hexahedron, 1);
  const DofMap dofs(mesh.num_nodes(), {});
  const DistributedDofs wrong = distribute_dofs(mesh, dofs, partition_elements(mesh, size + 1), size + 1);
  EXPECT_THROW(DistributedLinearSystem(MPI_COMM_WORLD, wrong, dofs), std::invalid_argument);
}

}  // namespace
}  // namespace hofem
