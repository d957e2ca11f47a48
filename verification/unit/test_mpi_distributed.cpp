// Distributed assembly into hypre and its solve, run by ctest on one
// rank (hofem_mpi_tests) and on two (mpi.two_ranks: mpirun -np 2): either way
// the answer must be the serial one.
#include "assembly/assembler.hpp"
#include "assembly/distributed_dofs.hpp"
#include "distributed/local_mesh.hpp"
#include "dynamics/dynamic_elasticity.hpp"
#include "material/material.hpp"
#include "mesh/box_mesh.hpp"
#include "distributed/mesh_partition.hpp"
#include "parallel/mpi_runtime.hpp"
#include "solver/distributed_system.hpp"
#include "linalg/linear_solver.hpp"
#include "study/manufactured_solution.hpp"
#include "solver/solver_factory.hpp"

#include <fmt/format.h>

#include <gtest/gtest.h>
#include <mpi.h>

namespace hofem {
namespace {

// Largest nodal displacement difference between a distributed body (this rank's
// nodes, owned and ghost) and a serial run of the same mesh, node by global id.
double largest_difference_on_piece(const DynamicElasticity& distributed, const Eigen::VectorXd& u_serial) {
  const LocalMesh& piece = distributed.distributed_mesh()->local;
  const Eigen::VectorXd u = distributed.displacement();
  double worst = 0.0;
  for (int n = 0; n < piece.mesh.num_nodes(); ++n)
    worst = std::max(worst, (u.segment<3>(3 * n) - u_serial.segment<3>(3 * piece.global_node[n])).norm());
  return worst;
}

// Linear elasticity on a P2 cube clamped at x = 0 under gravity. Each rank
// keeps its piece of the mesh and assembles only its own elements over it;
// hypre sums the shares. The distributed AMG-PCG solution equals the serial
// CHOLMOD one to 1e-9 relative: PCG stops at ||r|| <= 1e-12 ||b||, and the error
// is at most cond(K) (~1e3 here) times that. Each rank compares its local DOFs
// (owned and ghost) with the serial solution at the same global DOF.
TEST(DistributedSystem, EqualsTheSerialSolve) {
  ensure_hypre();
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  const Mesh mesh = box_mesh(BoxSpec{{0, 0, 0}, {2, 1, 1}, {6, 3, 3}}, CellType::Tetrahedron, 2);
  const DofMap dofs(mesh.num_nodes(), mesh.node_set("xmin"));
  const auto material = make_material("linear", LameParameters::from_young_poisson(1e3, 0.3));
  auto gravity = [](const Eigen::Vector3d&) { return Eigen::Vector3d(0, 0, -9.81); };

  const Assembler serial(mesh, dofs);
  SparseMatrix K = serial.new_matrix();
  Eigen::VectorXd g;
  serial.hessian(*material, Eigen::Map<const Eigen::VectorXd>(mesh.nodes.data(), 3 * mesh.num_nodes()), g, K, false);
  const Eigen::VectorXd b = dofs.restrict(serial.body_force_vector(gravity, 4));
  auto direct = make_linear_solver("cholmod");
  ASSERT_TRUE(direct->factorize(K));
  Eigen::VectorXd reference;
  direct->solve(b, reference);

  const DistributedMesh piece = distribute_mesh(MPI_COMM_WORLD, mesh);
  const Mesh& local = piece.mesh();
  const DofMap local_dofs(local.num_nodes(), local.node_set("xmin"));
  const Assembler assembler(local, local_dofs);
  SparseMatrix K_local = assembler.new_matrix();
  assembler.hessian(*material, Eigen::Map<const Eigen::VectorXd>(local.nodes.data(), 3 * local.num_nodes()), g,
                    K_local, false);
  Eigen::VectorXd b_local = local_dofs.restrict(assembler.body_force_vector(gravity, 4));
  const DistributedDofs rows = distribute_dofs(piece, local_dofs);
  rows.free.sum(b_local);  // this rank's elements' load -> the whole load at its DOFs
  DistributedLinearSystem system(rows);
  system.assemble_matrix(K_local);
  Eigen::VectorXd x;
  const DistributedSolveResult r = system.solve(b_local, x, 1e-12);
  EXPECT_TRUE(r.converged) << r.message;
  double worst = 0.0;
  for (int i = 0; i < local_dofs.num_free(); ++i) {
    const int dof = local_dofs.free_dofs()[i];
    const int serial_index = dofs.free_index(static_cast<int>(3 * piece.local.global_node[dof / 3] + dof % 3));
    ASSERT_GE(serial_index, 0);
    worst = std::max(worst, std::abs(x[i] - reference[serial_index]));
  }
  EXPECT_LE(worst, 1e-9 * reference.cwiseAbs().maxCoeff()) << "rank " << rank << " of " << size;
  // The ranks' rows together hold the serial matrix: every non-zero entry once
  // (entries summing to exactly zero across ranks may be stored as well).
  long long stored = system.local_nonzeros(), total = 0;
  MPI_Allreduce(&stored, &total, 1, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  long long nonzero = 0;
  for (Eigen::Index q = 0; q < K.nonZeros(); ++q) nonzero += K.valuePtr()[q] != 0.0;
  EXPECT_GE(total, nonzero);
  EXPECT_LE(total, K.nonZeros());
  EXPECT_EQ(rows.global_rows, dofs.num_free());
  if (size > 1) {  // really distributed: fewer rows, fewer nodes, a smaller pattern than the whole
    EXPECT_LT(rows.owned_rows, dofs.num_free());
    EXPECT_LT(local.num_nodes(), mesh.num_nodes());
    EXPECT_LT(K_local.nonZeros(), K.nonZeros());
  }
}

// GMRES and rigid-body modes (the options the issue names) reach the same
// solution; PCG without modes is the reference. The same tolerance argument.
TEST(DistributedSystem, GmresAndRigidBodyModesGiveTheSameSolution) {
  ensure_hypre();
  const Mesh mesh = box_mesh(BoxSpec{{0, 0, 0}, {2, 1, 1}, {4, 2, 2}}, CellType::Tetrahedron, 2);
  const auto material = make_material("linear", LameParameters::from_young_poisson(1e3, 0.3));
  const DistributedMesh piece = distribute_mesh(MPI_COMM_WORLD, mesh);
  const Mesh& local = piece.mesh();
  const DofMap dofs(local.num_nodes(), local.node_set("xmin"));
  const Assembler assembler(local, dofs);
  SparseMatrix K = assembler.new_matrix();
  Eigen::VectorXd g;
  assembler.hessian(*material, Eigen::Map<const Eigen::VectorXd>(local.nodes.data(), 3 * local.num_nodes()), g, K, false);
  Eigen::VectorXd b = dofs.restrict(assembler.body_force_vector([](const Eigen::Vector3d&) { return Eigen::Vector3d(0, 0, -1); }, 4));
  const DistributedDofs rows = distribute_dofs(piece, dofs);
  rows.free.sum(b);
  auto solve = [&](DistributedSolverOptions o, int& iterations) {
    DistributedLinearSystem system(rows, o);
    system.set_coordinates(local, dofs);
    system.assemble_matrix(K);
    Eigen::VectorXd x;
    const DistributedSolveResult r = system.solve(b, x, 1e-12);
    EXPECT_TRUE(r.converged) << o.krylov << ": " << r.message;
    iterations = r.iterations;
    return x;
  };
  int its_pcg = 0, its_gmres = 0, its_rigid = 0;
  const Eigen::VectorXd pcg = solve({}, its_pcg);
  const Eigen::VectorXd gmres = solve({.krylov = "gmres"}, its_gmres);
  const Eigen::VectorXd rigid = solve({.rigid_body_modes = true}, its_rigid);
  const double scale = rows.free.norm(pcg);
  EXPECT_LE(rows.free.norm(gmres - pcg), 1e-9 * scale);
  EXPECT_LE(rows.free.norm(rigid - pcg), 1e-9 * scale);
  RecordProperty("iterations pcg / gmres / pcg+rigid", fmt::format("{} / {} / {}", its_pcg, its_gmres, its_rigid));
  EXPECT_THROW(DistributedLinearSystem(rows, {.krylov = "bicgstab"}), std::invalid_argument);
  EXPECT_THROW(DistributedLinearSystem(rows, {.amg = "no-such-amg"}), std::invalid_argument);
}

// The manufactured-solution cube: the distributed
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
      hofem::MmsCase c;
      c.problem = problem;
      c.order = order;
      c.n = 3;  // 8 / 125 / 512 interior nodes for P1 / P2 / P3
      c.solver = SolverSpec::parse("cholmod");  // the serial reference: direct, Newton to 1e-10
      const hofem::MmsResult serial = hofem::run_mms(c);
      c.distributed = true;
      const hofem::MmsResult distributed = hofem::run_mms(c);
      const std::string what = fmt::format("{} P{}", problem, order);
      ASSERT_TRUE(serial.converged && distributed.converged) << what << ": " << distributed.message;
      EXPECT_EQ(distributed.newton_iterations, serial.newton_iterations) << what;
      EXPECT_EQ(distributed.cells, serial.cells) << what;  // the pieces count each element and node once
      EXPECT_EQ(distributed.nodes, serial.nodes) << what;
      EXPECT_EQ(distributed.dofs, serial.dofs) << what;
      EXPECT_NEAR(distributed.l2_error / serial.l2_error, 1.0, 1e-10) << what;
      EXPECT_NEAR(distributed.h1_error / serial.h1_error, 1.0, 1e-10) << what;
      RecordProperty(what + " l2 relative difference", fmt::format("{:.3g}", std::abs(distributed.l2_error / serial.l2_error - 1.0)));
    }
  // Unperturbed distributed cases run on pieces each rank generates itself
  // (box_piece); a perturbed one takes the other path, the whole mesh
  // partitioned by RCB on every rank. The same agreement either way.
  hofem::MmsCase c;
  c.order = 2;
  c.n = 3;
  c.perturbed = true;
  c.solver = SolverSpec::parse("cholmod");
  const hofem::MmsResult serial = hofem::run_mms(c);
  c.distributed = true;
  const hofem::MmsResult distributed = hofem::run_mms(c);
  ASSERT_TRUE(serial.converged && distributed.converged) << distributed.message;
  EXPECT_EQ(distributed.newton_iterations, serial.newton_iterations);
  EXPECT_NEAR(distributed.l2_error / serial.l2_error, 1.0, 1e-10);
  EXPECT_NEAR(distributed.h1_error / serial.h1_error, 1.0, 1e-10);
  EXPECT_EQ(distributed.nodes, serial.nodes);
  EXPECT_EQ(distributed.dofs, serial.dofs);
}

// The implicit integrator runs unchanged on top of the distributed
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
  DynamicsOptions o;
  o.integrator = Integrator::ImplicitEuler;
  o.dt = 0.02;
  o.gravity = Eigen::Vector3d(0, 0, -9.81);
  o.newton.linear_rtol = 1e-12;
  auto run = [&](DynamicElasticity& body, std::vector<int>& newton) {
    for (int k = 0; k < 10; ++k) {
      const StepReport r = body.step();
      EXPECT_TRUE(r.ok) << r.message;
      newton.push_back(r.newton_iterations);
    }
  };
  std::vector<int> newton_serial, newton_distributed;
  DynamicElasticity serial(mesh, *material, {PrescribedMotion{mesh.node_set("xmin"), {}, {}, {}}}, o);
  run(serial, newton_serial);
  o.distributed = true;
  DynamicElasticity distributed(mesh, *material, {PrescribedMotion{mesh.node_set("xmin"), {}, {}, {}}}, o);
  run(distributed, newton_distributed);
  EXPECT_EQ(newton_distributed, newton_serial);
  const Eigen::VectorXd u = distributed.displacement(), u_serial = serial.displacement();
  const double difference = largest_difference_on_piece(distributed, u_serial) / u_serial.cwiseAbs().maxCoeff();
  EXPECT_LE(difference, 1e-9) << "relative trajectory difference " << difference;
  EXPECT_GT(u_serial.cwiseAbs().maxCoeff(), 1e-3);  // it really moved
  // Whole-body quantities are sums over the ranks: the same as serial's.
  const Energies e = distributed.energies(), e_serial = serial.energies();
  // (Same tolerance as the positions: each term is a smooth function of them.)
  const double energy_scale = std::abs(e_serial.kinetic) + std::abs(e_serial.elastic) + std::abs(e_serial.gravity);
  EXPECT_NEAR(e.total(), e_serial.total(), 1e-9 * energy_scale);
  EXPECT_LE((distributed.linear_momentum() - serial.linear_momentum()).norm(), 1e-9 * serial.linear_momentum().norm());
  // The gathered field is the serial one, node for node, on rank 0.
  const Eigen::VectorXd gathered = distributed.distributed_mesh()->gather_nodal(u);
  if (distributed.distributed_mesh()->rank == 0) {
    ASSERT_EQ(gathered.size(), u_serial.size());
    EXPECT_LE((gathered - u_serial).cwiseAbs().maxCoeff(), 1e-9 * u_serial.cwiseAbs().maxCoeff());
  }
  RecordProperty("relative trajectory difference", fmt::format("{:.3g}", difference));
}

// Nodal terms on a distributed body: a P2 block thrown at a penalty floor with
// the lumped (HRZ) mass. Each floor term and each nodal mass is counted once
// over the ranks (the owner's), so the trajectory, the contact statistics and
// the energies are the serial ones, to the same tolerance as above.
TEST(DistributedSystem, FloorContactAndLumpedMassMatchSerial) {
  ensure_hypre();
  const Mesh mesh = box_mesh(BoxSpec{{0, 0, 0.05}, {1, 1, 0.55}, {4, 4, 2}}, CellType::Tetrahedron, 2);
  const auto material = make_material("neohookean", LameParameters::from_young_poisson(1e5, 0.3));
  DynamicsOptions o;
  o.integrator = Integrator::ImplicitEuler;
  o.dt = 0.01;
  o.mass = MassKind::Lumped;
  o.gravity = Eigen::Vector3d(0, 0, -9.81);
  o.floor = Floor{Eigen::Vector3d::UnitZ(), 0.0, 1e6};
  o.newton.linear_rtol = 1e-12;
  auto run = [&](DynamicElasticity& body) {
    body.set_velocity([](const Eigen::Vector3d&) { return Eigen::Vector3d(0.3, 0, -2.0); });
    for (int k = 0; k < 8; ++k) ASSERT_TRUE(body.step().ok);
  };
  DynamicElasticity serial(mesh, *material, {}, o);
  run(serial);
  o.distributed = true;
  DynamicElasticity distributed(mesh, *material, {}, o);
  run(distributed);
  EXPECT_GT(serial.stats().contact_node_steps, 0);  // it reached the floor
  EXPECT_EQ(distributed.stats().contact_node_steps, serial.stats().contact_node_steps);
  EXPECT_NEAR(distributed.stats().max_penetration, serial.stats().max_penetration, 1e-9 * serial.stats().max_penetration);
  const Eigen::VectorXd u_serial = serial.displacement();
  EXPECT_LE(largest_difference_on_piece(distributed, u_serial), 1e-9 * u_serial.cwiseAbs().maxCoeff());
  const Energies e = distributed.energies(), e_serial = serial.energies();
  const double scale = std::abs(e_serial.kinetic) + std::abs(e_serial.elastic) + std::abs(e_serial.gravity) + e_serial.floor;
  EXPECT_NEAR(e.floor, e_serial.floor, 1e-9 * scale);
  EXPECT_NEAR(e.total(), e_serial.total(), 1e-9 * scale);
  EXPECT_LE((distributed.linear_momentum() - serial.linear_momentum()).norm(), 1e-9 * serial.linear_momentum().norm());
}

}  // namespace
}  // namespace hofem
