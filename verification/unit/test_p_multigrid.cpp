// p-multigrid (thesis Alg. 3 over the orders p, p - 1, ..., 1 on one mesh): the
// prolongations reproduce the coarse spaces exactly, the V-cycle is SPD, and CG
// with it converges in a number of iterations that barely grows with the mesh.
#include "assembly/assembler.hpp"
#include "elastic_test_systems.hpp"
#include "material/material.hpp"
#include "mesh/box_mesh.hpp"
#include "problem/static_elasticity.hpp"
#include "linalg/krylov.hpp"
#include "linalg/linear_solver.hpp"
#include "solver/p_hierarchy.hpp"
#include "solver/p_multigrid.hpp"
#include "solver/solver_factory.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace hofem {
namespace {

// A linear-elastic unit cube (E = 1, nu = 0.3) with n cells per side, clamped at
// x = 0 (or free: the prolongation tests), and its stiffness over the free DOFs.
struct CubeSystem {
  Mesh mesh;
  DofMap dofs;
  SparseMatrix K;
  CubeSystem(int n, CellType cell, int order, bool clamped = true)
      : mesh(box_mesh(unit_cube(n), cell, order)),
        dofs(mesh.num_nodes(), clamped ? mesh.node_set("xmin") : std::vector<int>{}) {
    const Assembler a(mesh, dofs);
    const auto mat = make_material("linear", LameParameters::from_young_poisson(1.0, 0.3));
    Eigen::VectorXd g;
    K = a.new_matrix();
    a.hessian(*mat, Eigen::Map<const Eigen::VectorXd>(mesh.nodes.data(), 3 * mesh.num_nodes()), g, K, false);
  }
  CubeSystem(const CubeSystem&) = delete;  // the MeshView points into it
  MeshView mesh_view() const { return {&mesh, &dofs}; }
};

struct Element {
  CellType cell;
  int order;
  const char* name;
};
const Element kTet10{CellType::Tetrahedron, 2, "Tet10"}, kTet20{CellType::Tetrahedron, 3, "Tet20"},
    kTet35{CellType::Tetrahedron, 4, "Tet35"}, kHex20{CellType::Hexahedron, 2, "Hex20"};

Eigen::VectorXd rhs(Eigen::Index n) { return verification::smooth_rhs(n); }

// Interpolant of u on the free DOFs of a space: value of u's component c at the
// node of each listed global DOF.
template <class Field>
Eigen::VectorXd interpolate(const Mesh& m, const std::vector<int>& global_dofs, const Field& u) {
  Eigen::VectorXd v(static_cast<Eigen::Index>(global_dofs.size()));
  for (size_t i = 0; i < global_dofs.size(); ++i) v[i] = u(m.nodes.col(global_dofs[i] / 3))[global_dofs[i] % 3];
  return v;
}

// The order-1 level's nodes are the mesh's vertices in increasing node id
// (PHierarchy's numbering): their positions.
Eigen::Matrix3Xd vertex_positions(const Mesh& m) {
  std::vector<char> is_vertex(m.num_nodes(), 0);
  for (int e = 0; e < m.num_elements(); ++e)
    for (int j = 0; j < m.vertices_per_element(); ++j) is_vertex[m.elements(j, e)] = 1;
  std::vector<int> ids;
  for (int n = 0; n < m.num_nodes(); ++n)
    if (is_vertex[n]) ids.push_back(n);
  Eigen::Matrix3Xd X(3, static_cast<Eigen::Index>(ids.size()));
  for (size_t k = 0; k < ids.size(); ++k) X.col(static_cast<Eigen::Index>(k)) = m.nodes.col(ids[k]);
  return X;
}

// The product of the transfers from the order-1 level up to the fine level maps
// the order-1 interpolant of an affine field to its order-p interpolant: every
// coarser space lies in the finer one and each P is that inclusion. Checked for
// the direct hierarchy p -> 1 and the one-order-at-a-time hierarchy p -> ... -> 1
// (whose intermediate transfers a wrong weight or node order would break). The
// weights are basis values at reference nodes, exact to a few ulp, and a row sums
// at most (p + 1)(p + 2)(p + 3)/6 of them per level: 1e-13 relative is ample room
// while any wrong weight gives an O(1) error.
TEST(PMultigrid, ProlongationsReproduceAffineFieldsExactly) {
  const Eigen::Matrix3d B = (Eigen::Matrix3d() << 0.3, -1.2, 0.7, 2.0, 0.1, -0.4, -0.9, 0.5, 1.1).finished();
  const Eigen::Vector3d c(0.25, -1.5, 0.8), w(1.0, -2.0, 0.5);
  auto affine = [&](const Eigen::Vector3d& X) -> Eigen::Vector3d { return c + B * X; };
  // Vanishes on the clamped face x = 0, so clamping removes nothing from it.
  auto clamped_affine = [&](const Eigen::Vector3d& X) -> Eigen::Vector3d { return X[0] * w; };
  for (const Element& el : {kTet10, kTet20, kTet35, kHex20})
    for (bool by_one : {false, true})
      for (bool clamped : {false, true}) {
        if (by_one && el.cell == CellType::Hexahedron) continue;  // Hex20 -> Hex8 only
        const Mesh m = box_mesh(unit_cube(2), el.cell, el.order);
        const DofMap dofs(m.num_nodes(), clamped ? m.node_set("xmin") : std::vector<int>{});
        std::vector<int> orders{el.order};
        for (int q = el.order - 1; by_one && q > 1; --q) orders.push_back(q);
        orders.push_back(1);
        const PHierarchy h(m, dofs, orders);
        ASSERT_EQ(h.num_levels(), static_cast<int>(orders.size()));
        EXPECT_EQ(3 * h.level(0).num_free_nodes, dofs.num_free()) << el.name;
        // Coarse nodes: the 3^3 box vertices, less the 3^2 on the clamped face.
        const PLevel& coarse = h.level(h.num_levels() - 1);
        EXPECT_EQ(coarse.num_free_nodes, clamped ? 27 - 9 : 27) << el.name;
        const Eigen::Matrix3Xd X = vertex_positions(m);
        ASSERT_EQ(X.cols(), static_cast<Eigen::Index>(coarse.free_node.size()));
        for (int k = clamped ? 1 : 0; k < 2; ++k) {  // a general affine field is not zero on x = 0
          auto field = [&](const Eigen::Vector3d& x) { return k == 0 ? affine(x) : clamped_affine(x); };
          Eigen::VectorXd v(3 * coarse.num_free_nodes);
          for (Eigen::Index n = 0; n < X.cols(); ++n)
            if (coarse.free_node[n] >= 0) v.segment<3>(3 * coarse.free_node[n]) = field(X.col(n));
          for (int l = h.num_levels() - 2; l >= 0; --l) {
            Eigen::VectorXd finer;
            apply_nodal(h.transfer(l).P, v, finer);
            v = finer;
          }
          Eigen::VectorXd fine(dofs.num_free());
          for (int n = 0; n < m.num_nodes(); ++n)
            if (h.level(0).free_node[n] >= 0) fine.segment<3>(3 * h.level(0).free_node[n]) = field(m.nodes.col(n));
          EXPECT_LE((v - fine).cwiseAbs().maxCoeff(), 1e-13 * fine.cwiseAbs().maxCoeff())
              << el.name << (by_one ? " by one" : " to linear") << (clamped ? " clamped" : " free") << " field " << k;
        }
        // R is P^T, stored by rows.
        for (int l = 0; l + 1 < h.num_levels(); ++l)
          EXPECT_EQ((RowSparseMatrix(h.transfer(l).P.transpose()) - h.transfer(l).R).norm(), 0.0) << el.name;
      }
}

// The hierarchy refuses what it cannot build, with the reason.
TEST(PMultigrid, HierarchyRefusesInvalidOrders) {
  const Mesh m = box_mesh(unit_cube(1), CellType::Tetrahedron, 3);
  const DofMap dofs(m.num_nodes(), {});
  EXPECT_THROW(PHierarchy(m, dofs, {2, 1}), std::invalid_argument);     // not the mesh's order
  EXPECT_THROW(PHierarchy(m, dofs, {3, 2}), std::invalid_argument);     // does not end at 1
  EXPECT_THROW(PHierarchy(m, dofs, {3, 3, 1}), std::invalid_argument);  // not decreasing
  const Mesh hex = box_mesh(unit_cube(1), CellType::Hexahedron, 2);
  EXPECT_THROW(PHierarchy(hex, DofMap(hex.num_nodes(), {}), {2, 1, 1}), std::invalid_argument);
}

// M^-1 as a dense matrix from unit vectors. Symmetric: the pre- and post-smoothers
// are the same polynomial in D^-1 A_s (A_s: the level's single-precision copy, a
// symmetric matrix, which also forms the residuals), so M^-1 = 2S - S A_s S +
// (I - S A_s) C (I - A_s S) with S and C symmetric. The products accumulate in
// double, so only double rounding is left (observed <= 9.1e-16 relative): 1e-12.
// Positive definite: the eigenvalues of M^-1 A (via L^T M^-1 L, A = L L^T) are
// those of I minus the V-cycle's error propagator, in (0, 1] when the smoother
// contracts; the cycle is built from A_s, not A, so the upper end may exceed 1 by
// ~cond(A) * 6e-8 (float rounding; cond <= 1e3 here): 1e-4. The lower end is the
// cycle's quality: 1 - lambda_min is its convergence factor as a stationary
// iteration. Observed lambda_min, one order at a time / straight to order 1:
// Tet10 0.424, Tet20 0.455 / 0.215, Tet35 0.458 / 0.076, Hex20 0.552 (the reason
// ByOne is the default for tets). Below 0.05 means a broken smoother or transfer.
TEST(PMultigrid, VCycleIsSymmetricPositiveDefinite) {
  for (const Element& el : {kTet10, kTet20, kTet35, kHex20})
    for (auto coarsening : {PMultigridOptions::Coarsening::ByOne, PMultigridOptions::Coarsening::ToLinear}) {
      if (el.order == 2 && coarsening == PMultigridOptions::Coarsening::ToLinear) continue;  // the same hierarchy
      const CubeSystem s(el.cell == CellType::Hexahedron ? 3 : 2, el.cell, el.order);
      PMultigridOptions opt;
      opt.coarsening = coarsening;
      PMultigridPreconditioner M(opt);
      M.set_mesh_view(s.mesh_view());
      ASSERT_TRUE(M.setup(s.K)) << el.name << ": " << M.last_error();
      EXPECT_EQ(M.num_levels(), coarsening == PMultigridOptions::Coarsening::ByOne && el.cell == CellType::Tetrahedron
                                    ? el.order
                                    : 2)
          << el.name;
      const Eigen::MatrixXd Minv = verification::dense_inverse(M, s.K.rows());
      const char* how = coarsening == PMultigridOptions::Coarsening::ByOne ? " by one" : " to linear";
      EXPECT_LE((Minv - Minv.transpose()).cwiseAbs().maxCoeff(), 1e-12 * Minv.cwiseAbs().maxCoeff()) << el.name << how;
      const Eigen::MatrixXd S = 0.5 * (Minv + Minv.transpose());
      const Eigen::LLT<Eigen::MatrixXd> llt{Eigen::MatrixXd(s.K)};
      const Eigen::MatrixXd L = llt.matrixL();
      const Eigen::VectorXd eig =
          Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(L.transpose() * S * L, Eigen::EigenvaluesOnly).eigenvalues();
      EXPECT_GT(eig.minCoeff(), 0.0) << el.name << how;
      EXPECT_LE(eig.maxCoeff(), 1.0 + 1e-4) << el.name << how;
      EXPECT_GT(eig.minCoeff(), 0.05) << el.name << how << " lambda_min " << eig.minCoeff();
    }
}

struct CgRun {
  int iterations;
  Eigen::VectorXd x;
};

CgRun solve(const CubeSystem& s, const std::string& name, const Eigen::VectorXd& b) {
  KrylovOptions opt;
  opt.rtol = 1e-10;
  KrylovSolver cg(SolverMethod::Cg, make_preconditioner(name), opt);
  cg.set_mesh_view(s.mesh_view());
  EXPECT_TRUE(cg.factorize(s.K)) << name << ": " << cg.preconditioner().last_error();
  CgRun run{0, {}};
  cg.solve(b, run.x);
  run.iterations = cg.last_iterations();
  return run;
}

// K^-1 b by CHOLMOD: the reference of the iterative solves.
Eigen::VectorXd direct_solution(const CubeSystem& s, const Eigen::VectorXd& b) {
  auto direct = make_linear_solver("cholmod");
  EXPECT_TRUE(direct->factorize(s.K));
  Eigen::VectorXd x;
  direct->solve(b, x);
  return x;
}

// CG + pmg reaches 1e-10 and agrees with CHOLMOD: the relative error is bounded by
// cond(K) * 1e-10 with cond(K) ~1e3-1e4 on these small cubes, so 1e-5 is safe.
// It needs far fewer iterations than CG + Jacobi: observed (pmg / jacobi) Tet10
// 15 / 188, Tet20 14 / 363, Hex20 13 / 213; asserting 3x leaves room for any
// smoother setting while a broken coarse level (~Jacobi counts) fails.
TEST(PMultigrid, CgConvergesAndAgreesWithCholmod) {
  for (const Element& el : {kTet10, kTet20, kHex20}) {
    const CubeSystem s(el.cell == CellType::Hexahedron ? 4 : 3, el.cell, el.order);
    const Eigen::VectorXd b = rhs(s.K.rows());
    const Eigen::VectorXd x_ref = direct_solution(s, b);
    const CgRun pmg = solve(s, "pmg", b), jacobi = solve(s, "jacobi", b);
    EXPECT_LE((b - s.K * pmg.x).norm() / b.norm(), 1e-10) << el.name;
    EXPECT_LE((pmg.x - x_ref).norm() / x_ref.norm(), 1e-5) << el.name;
    EXPECT_LT(3 * pmg.iterations, jacobi.iterations)
        << el.name << ": pmg " << pmg.iterations << ", jacobi " << jacobi.iterations;
  }
}

// Above direct_coarse_limit the order-1 level is one BoomerAMG V-cycle instead of
// a factorisation (forced here with a limit of 0): CG still converges to the
// direct solution (the same cond(K) * 1e-10 bound as above) and, the coarse solve
// being inexact, in at most twice the iterations of the exact coarse level
// (observed amg / cholmod coarse: Tet10 18 / 15, Tet20 18 / 14, Hex20 17 / 13).
TEST(PMultigrid, AmgCoarseLevelConverges) {
  for (const Element& el : {kTet10, kTet20, kHex20}) {
    const CubeSystem s(el.cell == CellType::Hexahedron ? 4 : 3, el.cell, el.order);
    const Eigen::VectorXd b = rhs(s.K.rows());
    const Eigen::VectorXd x_ref = direct_solution(s, b);
    PMultigridOptions opt;
    opt.direct_coarse_limit = 0;
    PMultigridPreconditioner M(opt);
    M.set_mesh_view(s.mesh_view());
    ASSERT_TRUE(M.setup(s.K)) << el.name << ": " << M.last_error();
    EXPECT_FALSE(M.direct_coarse());
    KrylovOptions kopt;
    kopt.rtol = 1e-10;
    Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size());
    const KrylovResult r = conjugate_gradient(s.K, b, x, M, kopt);
    const int exact_coarse = solve(s, "pmg", b).iterations;
    ASSERT_TRUE(r.converged) << el.name << ": " << r.breakdown;
    EXPECT_LE((x - x_ref).norm() / x_ref.norm(), 1e-5) << el.name;
    EXPECT_LE(r.iterations, 2 * exact_coarse) << el.name << ": amg coarse " << r.iterations << ", cholmod coarse "
                                              << exact_coarse;
  }
}

// Multigrid's promise: iterations independent of h. The smoother and the
// transfers are fixed per order, so the V-cycle's convergence factor is bounded
// independently of h (the boundary layers aside). The target: at most 3
// more iterations from n = 2 to the largest n (observed P2 15, 15, 14; P3 15, 14,
// 14 at rtol 1e-10); CG + Jacobi grows ~1.8x per halving
// of h (116, 223, 406 at P2, rtol 1e-8), so an h-dependent cycle fails.
TEST(PMultigrid, IterationsNearlyFlatUnderRefinement) {
  for (const Element& el : {kTet10, kTet20}) {
    std::vector<int> its;
    for (int n : {2, 4, 8}) {
      const CubeSystem s(n, el.cell, el.order);
      its.push_back(solve(s, "pmg", rhs(s.K.rows())).iterations);
    }
    const int lo = *std::min_element(its.begin(), its.end()), hi = *std::max_element(its.begin(), its.end());
    EXPECT_LE(hi - lo, 3) << el.name << " iterations n=2,4,8: " << its[0] << ", " << its[1] << ", " << its[2];
  }
}

// The coarse operator's values change with every setup (Newton iteration), its
// pattern does not: one CHOLMOD symbolic analysis serves every setup.
TEST(PMultigrid, CoarseAnalysisIsReusedAcrossSetups) {
  const CubeSystem s(2, CellType::Tetrahedron, 2);
  PMultigridPreconditioner M;
  M.set_mesh_view(s.mesh_view());
  ASSERT_TRUE(M.setup(s.K));
  Eigen::VectorXd z1, z2;
  const Eigen::VectorXd r = rhs(s.K.rows());
  M.apply(r, z1);
  const SparseMatrix K2 = 2.0 * s.K;
  ASSERT_TRUE(M.setup(K2));
  M.apply(r, z2);
  EXPECT_EQ(M.coarse_analyses(), 1);
  // M^-1 is homogeneous of degree -1 in A (the eigenvalue estimate scales too):
  // equal to rounding.
  EXPECT_LE((2.0 * z2 - z1).norm(), 1e-12 * z1.norm());
}

// The hierarchy is cached per DOF map by its identity, not its address: a
// problem that rebuilds its DOF map in place (a released node set) hands the
// preconditioner the same pointers with different free DOFs, and CG + pmg must
// solve the new system. (Keyed by address, the stale hierarchy's transfers
// have the old level sizes.) CG stops at a relative residual of 1e-10; the true
// residual is checked at 1e-8, leaving 100x for the recurrence's drift.
TEST(PMultigrid, RebuildsForADofMapRebuiltAtTheSameAddress) {
  CubeSystem s(2, CellType::Tetrahedron, 2);
  const auto solver = make_linear_solver("cg+pmg");
  solver->set_relative_tolerance(1e-10);
  const auto solve_and_check = [&](const SparseMatrix& K) {
    solver->set_mesh_view(s.mesh_view());
    ASSERT_TRUE(solver->factorize(K)) << solver->last_error();
    const Eigen::VectorXd b = rhs(K.rows());
    Eigen::VectorXd x;
    solver->solve(b, x);
    EXPECT_LE((K * x - b).norm(), 1e-8 * b.norm());
  };
  solve_and_check(s.K);
  const std::uint64_t before = s.dofs.identity();
  std::vector<int> clamped = s.mesh.node_set("xmin");
  for (int n : s.mesh.node_set("xmax")) clamped.push_back(n);
  s.dofs = DofMap(s.mesh.num_nodes(), clamped);  // same address, fewer free DOFs
  EXPECT_NE(s.dofs.identity(), before);
  const Assembler a(s.mesh, s.dofs);
  const auto mat = make_material("linear", LameParameters::from_young_poisson(1.0, 0.3));
  Eigen::VectorXd g;
  SparseMatrix K2 = a.new_matrix();
  a.hessian(*mat, Eigen::Map<const Eigen::VectorXd>(s.mesh.nodes.data(), 3 * s.mesh.num_nodes()), g, K2, false);
  ASSERT_LT(K2.rows(), s.K.rows());
  solve_and_check(K2);
}

// Newton on a Neo-Hookean cube with CG + pmg: the static solver hands the
// preconditioner its mesh, pmg is set up again for every Newton Hessian, and the
// solution is CHOLMOD's. Both stop at |g| <= 1e-10 of the load, so they agree
// to ~cond(K) * 1e-10 (cond ~1e3 here): 1e-6 relative.
TEST(PMultigrid, DrivesNewtonOnANonlinearMaterial) {
  for (const Element& el : {kTet10, kHex20}) {
    const Mesh m = box_mesh(unit_cube(3), el.cell, el.order);
    const auto ref = verification::solve_pulled_neohookean(m, "cholmod");
    const auto pmg = verification::solve_pulled_neohookean(m, "cg+pmg");
    ASSERT_TRUE(ref.converged && pmg.converged) << el.name << ": " << ref.message << " / " << pmg.message;
    EXPECT_LE((ref.displacement - pmg.displacement).norm() / ref.displacement.norm(), 1e-6) << el.name;
  }
}

TEST(PMultigrid, RefusesWithoutMeshViewAndOnOrderOne) {
  const CubeSystem p2(2, CellType::Tetrahedron, 2);
  auto M = make_preconditioner("pmg");
  EXPECT_FALSE(M->setup(p2.K));
  EXPECT_NE(M->last_error().find("set_mesh_view"), std::string::npos) << M->last_error();
  EXPECT_TRUE(preconditioner_needs_mesh_view("pmg"));
  // Order 1 has no coarser p level: a clear failure, for tets and Hex8 alike.
  for (CellType cell : {CellType::Tetrahedron, CellType::Hexahedron}) {
    const CubeSystem p1(2, cell, 1);
    auto M1 = make_preconditioner("pmg");
    M1->set_mesh_view(p1.mesh_view());
    EXPECT_FALSE(M1->setup(p1.K));
    EXPECT_NE(M1->last_error().find("pmg needs element order >= 2"), std::string::npos) << M1->last_error();
  }
  // Newton passes the reason on instead of only "not positive definite".
  {
    const Mesh m = box_mesh(unit_cube(2), CellType::Tetrahedron, 1);
    const auto mat = make_material("neohookean", LameParameters::from_young_poisson(1.0, 0.3));
    VectorField pull = [](const Eigen::Vector3d& X) { return Eigen::Vector3d(0.1 * X[0], 0.0, 0.0); };
    StaticOptions opt;
    opt.solver = SolverSpec::parse("cg+pmg");
    StaticElasticity p(m, *mat, {{m.node_set("xmin"), nullptr}, {m.node_set("xmax"), pull}}, nullptr, opt);
    const StaticReport r = p.solve();
    EXPECT_FALSE(r.converged);
    EXPECT_NE(r.message.find("pmg needs element order >= 2"), std::string::npos) << r.message;
  }
  // A matrix that does not belong to the DOF map.
  auto M2 = make_preconditioner("pmg");
  const CubeSystem other(3, CellType::Tetrahedron, 2);
  M2->set_mesh_view(p2.mesh_view());
  EXPECT_FALSE(M2->setup(other.K));
  EXPECT_NE(M2->last_error().find("free DOFs"), std::string::npos) << M2->last_error();
}

}  // namespace
}  // namespace hofem
