// Element-block Additive-Schwarz preconditioner (Longva et al. 2020 eq. 13-14): exact
// inverse for a single block, the reflected pseudo-inverse of eq. 14 on an
// indefinite block, SPD on stiffness matrices, convergence of CG and MINRES to
// CHOLMOD's solution, Jacobi on uncovered DOFs, reproducibility, error paths.
#include "assembly/assembler.hpp"
#include "elastic_test_systems.hpp"
#include "material/material.hpp"
#include "mesh/box_mesh.hpp"
#include "solver/additive_schwarz.hpp"
#include "linalg/krylov.hpp"
#include "solver/solver_factory.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <limits>

namespace hofem {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// A clamped (xmin) unit cube with a linear-elastic stiffness matrix.
using System = verification::ClampedElasticBody;
using verification::dense_inverse;

// One unconstrained Tet4: a single block of all 12 DOFs, so S = C_K^+ of the whole matrix.
struct OneTet {
  Mesh mesh;
  DofMap dofs;
  OneTet() {
    mesh.cell = CellType::Tetrahedron;
    mesh.nodes = Eigen::Matrix3Xd::Zero(3, 4);
    mesh.nodes.block<3, 3>(0, 1).setIdentity();
    mesh.elements.resize(4, 1);
    mesh.elements << 0, 1, 2, 3;
    dofs = DofMap(4, {});
  }
  MeshView mesh_view() const { return {&mesh, &dofs}; }
};

// C = Q diag(lambda) Q^T with a random orthogonal Q (fixed seed via Eigen's rand).
Eigen::MatrixXd with_spectrum(const Eigen::VectorXd& lambda, Eigen::MatrixXd& Q) {
  std::srand(7);
  Q = Eigen::HouseholderQR<Eigen::MatrixXd>(Eigen::MatrixXd::Random(lambda.size(), lambda.size())).householderQ();
  return Q * lambda.asDiagonal() * Q.transpose();
}

SparseMatrix sparse(const Eigen::MatrixXd& D) { return D.sparseView(); }

Eigen::VectorXd rhs(Eigen::Index n) { return verification::smooth_rhs(n); }

TEST(AdditiveSchwarz, SingleBlockIsTheInverseOfAnSpdMatrix) {
  const OneTet tet;
  Eigen::MatrixXd Q;
  const Eigen::VectorXd lambda = Eigen::VectorXd::LinSpaced(12, 1.0, 10.0);
  const Eigen::MatrixXd C = with_spectrum(lambda, Q);
  const Eigen::MatrixXd Cinv = C.inverse();
  for (const bool cholesky : {true, false}) {  // fast path and eigen-decomposition
    AdditiveSchwarzOptions options;
    options.cholesky_fast_path = cholesky;
    AdditiveSchwarzPreconditioner S(options);
    S.set_mesh_view(tet.mesh_view());
    ASSERT_TRUE(S.setup(sparse(C))) << S.last_error();
    EXPECT_EQ(S.num_blocks(), 1);
    EXPECT_EQ(S.num_uncovered(), 0);
    EXPECT_EQ(S.num_truncated(), 0);
    // Eigen-decomposition, Cholesky and inversion are backward stable: each inverse
    // is off by ~cond(C) n eps = 10 * 12 * 2.2e-16 ~ 3e-14 relative; 1e-12 leaves 30x.
    EXPECT_LE((dense_inverse(S, 12) - Cinv).norm(), 1e-12 * Cinv.norm()) << "cholesky " << cholesky;
  }
}

// Eq. 14 on a constructed indefinite block with eigenvalues down to -5, two of them
// below eps lambda_max. epsilon = 1e-8 makes the truncated value eps / lambda_max =
// 1.4e-9 large enough to measure against rounding of order n eps ||S|| ~ 3e-14.
TEST(AdditiveSchwarz, ReflectsAndTruncatesEigenvaluesAsEq14) {
  const OneTet tet;
  const double eps = 1e-8, lmax = 7.0;
  Eigen::VectorXd lambda(12), reflected(12);
  lambda << -5, -2, -0.1, 0.1, 0.5, 1, 2, 3, 4, lmax, 1e-12, -3e-11;
  for (int k = 0; k < 12; ++k) reflected[k] = std::abs(lambda[k]) >= eps * lmax ? 1.0 / std::abs(lambda[k]) : eps / lmax;
  Eigen::MatrixXd Q;
  const Eigen::MatrixXd C = with_spectrum(lambda, Q);
  AdditiveSchwarzPreconditioner S({{}, eps});
  S.set_mesh_view(tet.mesh_view());
  ASSERT_TRUE(S.setup(sparse(C))) << S.last_error();
  EXPECT_EQ(S.num_truncated(), 2);
  EXPECT_EQ(S.num_reflected(), 3);  // -5, -2, -0.1 (-3e-11 is truncated instead)
  const Eigen::MatrixXd expected = Q * reflected.asDiagonal() * Q.transpose();
  const Eigen::MatrixXd Minv = dense_inverse(S, 12);
  EXPECT_EQ(Minv, Eigen::MatrixXd(S.block_inverse(0)));
  // Backward error ~n eps ||C|| = 2e-14 moves the kept eigenvalues (|lambda| >= 0.1)
  // and the eigenvectors (gaps >= 0.1) by <= 2e-13 relative; ||S|| = 10, so entries
  // are off by ~2e-12 at worst: 1e-11 of ||S||.
  EXPECT_LE((Minv - expected).cwiseAbs().maxCoeff(), 1e-11 * expected.cwiseAbs().maxCoeff());
  // The truncated directions get eps / lambda_max (not 0, not 1/|lambda|): to
  // rounding 3e-14 over 1.4e-9, i.e. 1e-4 relative with margin.
  for (int k : {10, 11}) EXPECT_NEAR(Q.col(k).dot(Minv * Q.col(k)), eps / lmax, 1e-4 * eps / lmax);
  // SPD although C is indefinite: exactly symmetric (S_K is symmetrised), and the
  // smallest eigenvalue is the truncated one, eps / lambda_max > 0.
  EXPECT_EQ((Minv - Minv.transpose()).cwiseAbs().maxCoeff(), 0.0);
  const double min_eig = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Minv).eigenvalues().minCoeff();
  EXPECT_NEAR(min_eig, eps / lmax, 1e-4 * eps / lmax);
}

// Default eps = 1e-13: a block singular to working precision (lambda = 1e-20 next
// to 7) gets eps / lambda_max = 1.4e-14 in that direction. Rounding of S (norm 1/7)
// is <= n eps ||S|| = 3.8e-16, 3% of the value: checked to 10%.
TEST(AdditiveSchwarz, NearlySingularBlockGetsEpsOverLambdaMax) {
  const OneTet tet;
  Eigen::VectorXd lambda = Eigen::VectorXd::Constant(12, 7.0);
  lambda[4] = 1e-20;
  Eigen::MatrixXd Q;
  const Eigen::MatrixXd C = with_spectrum(lambda, Q);
  AdditiveSchwarzPreconditioner S;
  S.set_mesh_view(tet.mesh_view());
  ASSERT_TRUE(S.setup(sparse(C))) << S.last_error();
  EXPECT_EQ(S.num_truncated(), 1);
  const Eigen::MatrixXd Minv = dense_inverse(S, 12);
  EXPECT_NEAR(Q.col(4).dot(Minv * Q.col(4)), 1e-13 / 7.0, 0.1 * 1e-13 / 7.0);
  EXPECT_NEAR(Q.col(0).dot(Minv * Q.col(0)), 1.0 / 7.0, 1e-14);  // kept: 1/7 to ~n eps
}

// M^-1 assembled from blocks: symmetric (S_K exactly symmetric and summed in the
// same order for (i, j) and (j, i), so the 1e-12 bound is met with room) and
// positive definite. These systems are SPD, cond <= ~1e3, min eig of M^-1 well
// above rounding.
TEST(AdditiveSchwarz, IsSymmetricPositiveDefiniteOnStiffnessMatrices) {
  const System systems[] = {{CellType::Tetrahedron, 1, 2}, {CellType::Tetrahedron, 2, 2}, {CellType::Hexahedron, 1, 3}};
  for (const System& s : systems) {
    AdditiveSchwarzPreconditioner M;
    M.set_mesh_view(s.mesh_view());
    ASSERT_TRUE(M.setup(s.K)) << M.last_error();
    EXPECT_EQ(M.num_blocks(), s.mesh.num_elements());
    // Eq. 13: C_K is the submatrix of the global K on the element's DOFs (not the
    // element matrix), so S_K C_K = I. cond(C_K) <= ~1e3 for these well-shaped
    // elements, so the product is I to ~cond n eps <= 1e-11; checked to 1e-9.
    const Eigen::MatrixXd D(s.K);
    for (int b = 0; b < M.num_blocks(); b += 7) {
      const std::span<const int> d = M.block_dofs(b);
      Eigen::MatrixXd C(d.size(), d.size());
      for (size_t i = 0; i < d.size(); ++i)
        for (size_t j = 0; j < d.size(); ++j) C(i, j) = D(d[i], d[j]);
      EXPECT_LE((M.block_inverse(b) * C - Eigen::MatrixXd::Identity(C.rows(), C.cols())).norm(), 1e-9) << "block " << b;
    }
    const Eigen::MatrixXd Minv = dense_inverse(M, s.K.rows());
    EXPECT_LE((Minv - Minv.transpose()).cwiseAbs().maxCoeff(), 1e-12 * Minv.cwiseAbs().maxCoeff());
    const Eigen::VectorXd eig = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Minv).eigenvalues();
    EXPECT_GT(eig.minCoeff(), 1e-8 * eig.maxCoeff()) << s.mesh.nodes_per_element() << "-node elements";
  }
}

// Relative residual 1e-10 bounds the relative error by cond(K) 1e-10 with cond(K)
// ~1e3-1e4 here, so 1e-5 is safe. (No claim on iterations against Jacobi: a
// one-level Schwarz method without coarse space has the same h^-2 growth; on
// uncut meshes it is within 0.9-1.7x of Jacobi's count, see additive_schwarz.cpp.)
TEST(AdditiveSchwarz, CgAndMinresConvergeToTheCholmodSolution) {
  const System systems[] = {{CellType::Tetrahedron, 2, 3}, {CellType::Hexahedron, 2, 3}};
  for (const System& s : systems) {
    const Eigen::VectorXd b = rhs(s.K.rows());
    auto direct = make_linear_solver("cholmod");
    ASSERT_TRUE(direct->factorize(s.K));
    Eigen::VectorXd x_ref, x;
    direct->solve(b, x_ref);
    KrylovOptions opt;
    opt.rtol = 1e-10;
    for (const SolverMethod method : {SolverMethod::Cg, SolverMethod::Minres}) {
      KrylovSolver k(method, make_preconditioner("schwarz"), opt);
      k.set_mesh_view(s.mesh_view());
      ASSERT_TRUE(k.factorize(s.K)) << k.name();
      k.solve(b, x);
      EXPECT_TRUE(k.last_result().converged) << k.name();
      EXPECT_LE((x - x_ref).norm() / x_ref.norm(), 1e-5) << k.name() << ", " << s.mesh.nodes_per_element() << " nodes";
    }
  }
}

// A Neo-Hookean Hessian under strong compression (stretch down to 0.4), without
// PSD projection, has 17 negative eigenvalues (P2, n = 2) and element blocks with
// 7 negative eigenvalues between them, which eq. 14 reflects. M^-1 stays SPD, so
// MINRES applies and converges to UMFPACK's solution. cond(K) = max|lambda| /
// min|lambda| = 3.0e3 here, so a relative residual of 1e-10 bounds the error by
// 3e-7; checked to 1e-5.
TEST(AdditiveSchwarz, MinresConvergesOnAnIndefiniteHessian) {
  System s(CellType::Tetrahedron, 2, 2);
  const Assembler a(s.mesh, s.dofs);
  const auto mat = make_material("neohookean", LameParameters::from_young_poisson(1.0, 0.3));
  Eigen::VectorXd x(3 * s.mesh.num_nodes()), g;
  for (int i = 0; i < s.mesh.num_nodes(); ++i) {
    const Eigen::Vector3d X = s.mesh.nodes.col(i);
    x.segment<3>(3 * i) = Eigen::Vector3d(X[0] * (1 - 0.3 * X[0]), X[1] + 0.3 * X[0] * X[2], X[2]);
  }
  a.hessian(*mat, x, g, s.K, false);
  const Eigen::MatrixXd D(s.K);
  ASSERT_LT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(D, Eigen::EigenvaluesOnly).eigenvalues()[0], 0.0);
  AdditiveSchwarzPreconditioner M;
  M.set_mesh_view(s.mesh_view());
  ASSERT_TRUE(M.setup(s.K)) << M.last_error();
  EXPECT_GT(M.num_reflected(), 0);
  const Eigen::MatrixXd Minv = dense_inverse(M, s.K.rows());
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Minv, Eigen::EigenvaluesOnly).eigenvalues()[0], 0.0);
  const Eigen::VectorXd b = rhs(s.K.rows());
  auto lu = make_linear_solver("umfpack");
  ASSERT_TRUE(lu->factorize(s.K));
  Eigen::VectorXd x_ref, u = Eigen::VectorXd::Zero(b.size());
  lu->solve(b, x_ref);
  KrylovOptions opt;
  opt.rtol = 1e-10;
  const KrylovResult r = minres(s.K, b, u, M, opt);
  EXPECT_TRUE(r.converged) << r.breakdown << " after " << r.iterations;
  EXPECT_LE((u - x_ref).norm() / x_ref.norm(), 1e-5);
}

// Blocks for a subset of elements only: DOFs in none of them get r_i / A_ii.
TEST(AdditiveSchwarz, SubsetOfElementsLeavesOtherDofsJacobiPreconditioned) {
  const System s(CellType::Tetrahedron, 2, 3);
  AdditiveSchwarzOptions options;
  for (int e = 0; e < s.mesh.num_elements(); e += 5) options.elements.push_back(e);
  AdditiveSchwarzPreconditioner M(options);
  M.set_mesh_view(s.mesh_view());
  ASSERT_TRUE(M.setup(s.K)) << M.last_error();
  EXPECT_EQ(M.num_blocks(), static_cast<int>(options.elements.size()));
  ASSERT_GT(M.num_uncovered(), 0);
  std::vector<char> covered(s.K.rows(), 0);
  for (int b = 0; b < M.num_blocks(); ++b)
    for (int f : M.block_dofs(b)) covered[f] = 1;
  const Eigen::VectorXd r = rhs(s.K.rows());
  Eigen::VectorXd z;
  M.apply(r, z);
  int checked = 0;
  for (Eigen::Index f = 0; f < r.size(); ++f)
    if (!covered[f]) {
      // (1 / A_ii) r_i against r_i / A_ii: two roundings apart at most.
      EXPECT_NEAR(z[f], r[f] / s.K.coeff(f, f), 2 * kEps * std::abs(z[f])) << "DOF " << f;
      ++checked;
    }
  EXPECT_EQ(checked, M.num_uncovered());
  KrylovOptions opt;
  opt.rtol = 1e-10;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(r.size());
  EXPECT_TRUE(conjugate_gradient(s.K, r, x, M, opt).converged);
}

// Each DOF sums its block contributions in a fixed order: apply() gives the same
// bits on 1 and 2 threads (P2 n = 4: 384 blocks of 30 DOFs, 3.5e5 stored
// entries, above the parallel threshold).
TEST(AdditiveSchwarz, BitwiseReproducibleAcrossThreadCounts) {
  const System s(CellType::Tetrahedron, 2, 4);
  const Eigen::VectorXd r = rhs(s.K.rows());
  const int previous = omp_get_max_threads();
  Eigen::VectorXd z[2];
  for (int threads : {1, 2}) {
    omp_set_num_threads(threads);
    AdditiveSchwarzPreconditioner M;
    M.set_mesh_view(s.mesh_view());
    ASSERT_TRUE(M.setup(s.K)) << M.last_error();
    M.apply(r, z[threads - 1]);
  }
  omp_set_num_threads(previous);
  EXPECT_EQ(z[0], z[1]);
}

// The block-to-value map is rebuilt when A's pattern changes: with only K's
// diagonal every S_K is diagonal, and M^-1 r = c_i r_i / K_ii with c_i the number
// of blocks holding DOF i (to c_i + 2 roundings, c_i <= 8 for Hex8: 16 eps bounds
// it); K again gives the first result, bit for bit.
TEST(AdditiveSchwarz, FollowsAChangeOfSparsityPattern) {
  const System s(CellType::Hexahedron, 1, 2);
  AdditiveSchwarzPreconditioner M;
  M.set_mesh_view(s.mesh_view());
  const Eigen::VectorXd r = rhs(s.K.rows());
  Eigen::VectorXd z0, z1, z2;
  ASSERT_TRUE(M.setup(s.K)) << M.last_error();
  M.apply(r, z0);
  const SparseMatrix diagonal = SparseMatrix(s.K.diagonal().asDiagonal());
  ASSERT_TRUE(M.setup(diagonal)) << M.last_error();
  M.apply(r, z1);
  Eigen::VectorXd count = Eigen::VectorXd::Zero(r.size());
  for (int b = 0; b < M.num_blocks(); ++b)
    for (int f : M.block_dofs(b)) count[f] += 1.0;
  const Eigen::VectorXd expected = count.cwiseProduct(r).cwiseQuotient(s.K.diagonal());
  EXPECT_LE((z1 - expected).cwiseAbs().maxCoeff(), 16 * kEps * expected.cwiseAbs().maxCoeff());
  ASSERT_TRUE(M.setup(s.K)) << M.last_error();
  M.apply(r, z2);
  EXPECT_EQ(z0, z2);
}

TEST(AdditiveSchwarz, SetupFailsWithAReason) {
  const System s(CellType::Tetrahedron, 1, 2);
  auto M = make_preconditioner("schwarz");
  EXPECT_EQ(M->name(), "schwarz");
  EXPECT_FALSE(M->setup(s.K));
  EXPECT_NE(M->last_error().find("set_mesh_view"), std::string::npos) << M->last_error();
  M->set_mesh_view(s.mesh_view());
  SparseMatrix bad = s.K;
  bad.valuePtr()[bad.nonZeros() / 2] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(M->setup(bad));
  EXPECT_NE(M->last_error().find("nan"), std::string::npos) << M->last_error();
  EXPECT_TRUE(M->setup(s.K)) << M->last_error();  // recovers on a good matrix
  AdditiveSchwarzPreconditioner out_of_range({{0, s.mesh.num_elements()}, 1e-13});
  out_of_range.set_mesh_view(s.mesh_view());
  EXPECT_FALSE(out_of_range.setup(s.K));
  EXPECT_NE(out_of_range.last_error().find("out of range"), std::string::npos) << out_of_range.last_error();
}

}  // namespace
}  // namespace hofem
