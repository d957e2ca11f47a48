// Krylov solvers and preconditioners on matrices from the elasticity core: every
// combination agrees with CHOLMOD on an SPD system; on an indefinite one CG
// reports the breakdown while CR, MINRES and GMRES converge; preconditioners are SPD.
#include "assembly/assembler.hpp"
#include "elastic_test_systems.hpp"
#include "material/material.hpp"
#include "mesh/box_mesh.hpp"
#include "problem/static_elasticity.hpp"
#include "linalg/blas_threads.hpp"
#include "linalg/krylov.hpp"
#include "linalg/linear_solver.hpp"
#include "solver/solver_factory.hpp"

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include <omp.h>

#include <algorithm>
#include <iostream>

extern "C" int openblas_get_num_threads(void);  // OpenBLAS's public API (cblas.h)

namespace hofem {
namespace {

using verification::ClampedElasticBody;
using verification::dense_inverse;

// A P2 tetrahedral bar clamped at x = 0, ~600 unknowns.
struct BarSystem : ClampedElasticBody {
  BarSystem() : ClampedElasticBody(box_mesh(BoxSpec{{0, 0, 0}, {2, 1, 1}, {4, 2, 2}}, CellType::Tetrahedron, 2)) {}
};

const BarSystem& bar() {
  static const BarSystem system;
  return system;
}

SparseMatrix stiffness() { return bar().K; }

// Preconditioners this binary tests. BoomerAMG starts MPI, whose start-up
// allocations LeakSanitizer cannot attribute; it is tested in hofem_mpi_tests.
std::vector<std::string> serial_preconditioners() {
  std::vector<std::string> names;
  for (const std::string& n : preconditioner_names())
    if (n.rfind("amg", 0) != 0) names.push_back(n);
  return names;
}

Eigen::VectorXd rhs(Eigen::Index n) { return verification::smooth_rhs(n); }

// The direct solution the iterative ones are measured against (empty if K is not SPD).
Eigen::VectorXd cholmod_solution(const SparseMatrix& K, const Eigen::VectorXd& b) {
  auto direct = make_linear_solver("cholmod");
  Eigen::VectorXd x;
  if (direct->factorize(K)) direct->solve(b, x);
  return x;
}

// Relative residual 1e-10 bounds the relative error by cond(K) * 1e-10; cond(K)
// of this small clamped bar is ~1e3-1e4 (P2, 600 unknowns), so 1e-5 is safe and
// still orders of magnitude below any wrong answer.
TEST(Krylov, EveryMethodAndPreconditionerAgreesWithCholmodOnSpd) {
  const SparseMatrix K = stiffness();
  const Eigen::VectorXd b = rhs(K.rows());
  const Eigen::VectorXd x_ref = cholmod_solution(K, b);
  ASSERT_EQ(x_ref.size(), b.size());
  KrylovOptions opt;
  opt.rtol = 1e-10;
  for (const SolverMethod method : {SolverMethod::Cg, SolverMethod::Cr, SolverMethod::Minres, SolverMethod::Gmres})
    for (const std::string& pc : serial_preconditioners()) {
      KrylovSolver s(method, make_preconditioner(pc), opt);
      s.set_mesh_view(bar().mesh_view());
      ASSERT_TRUE(s.factorize(K)) << s.name();
      Eigen::VectorXd x;
      s.solve(b, x);
      EXPECT_TRUE(s.last_result().converged) << s.name();
      EXPECT_LE((b - K * x).norm() / b.norm(), opt.rtol) << s.name();
      EXPECT_LE((x - x_ref).norm() / x_ref.norm(), 1e-5) << s.name() << " after " << s.last_result().iterations;
      EXPECT_EQ(s.last_result().history.size(), static_cast<size_t>(s.last_result().iterations) + 1) << s.name();
    }
}

TEST(Krylov, PreconditioningReducesIterations) {
  const SparseMatrix K = stiffness();
  const Eigen::VectorXd b = rhs(K.rows());
  auto iterations = [&](const char* pc) {
    KrylovSolver s(SolverMethod::Cg, make_preconditioner(pc));
    s.factorize(K);
    Eigen::VectorXd x;
    s.solve(b, x);
    return s.last_result().iterations;
  };
  const int none = iterations("none"), jacobi = iterations("jacobi"), ic = iterations("ic0");
  EXPECT_LT(jacobi, none);
  EXPECT_LT(ic, jacobi);
}

// A fixed budget (set_fixed_iterations, the thesis §5.3.2's "3 iterations CG")
// runs exactly k iterations and returns the iterate without converging; k = 0
// restores convergence to the tolerance. Each CG iterate minimises the energy
// norm of the error over a Krylov space that grows with k, so 12 iterations
// leave a smaller energy error than 3 (the residual itself need not shrink:
// measured 0.51 after 3, 0.77 after 12 on this bar).
TEST(Krylov, FixedIterationsStopAfterExactlyKAndAcceptTheIterate) {
  const SparseMatrix K = stiffness();
  const Eigen::VectorXd b = rhs(K.rows());
  const Eigen::VectorXd x_ref = cholmod_solution(K, b);
  ASSERT_EQ(x_ref.size(), b.size());
  auto energy_error = [&](const Eigen::VectorXd& x) { return (x - x_ref).dot(K * (x - x_ref)); };
  KrylovSolver s(SolverMethod::Cg, make_preconditioner("jacobi"));
  ASSERT_TRUE(s.set_fixed_iterations(3));
  ASSERT_TRUE(s.factorize(K));
  Eigen::VectorXd x;
  s.solve(b, x);  // does not throw although it has not converged
  EXPECT_EQ(s.last_iterations(), 3);
  EXPECT_FALSE(s.last_result().converged);
  const double e3 = energy_error(x);
  s.set_fixed_iterations(12);
  s.solve(b, x);
  EXPECT_EQ(s.last_iterations(), 12);
  EXPECT_LT(energy_error(x), e3);
  s.set_fixed_iterations(0);
  s.solve(b, x);
  EXPECT_TRUE(s.last_result().converged);
  EXPECT_GT(s.last_iterations(), 12);
  // A direct solver has no iterations to fix.
  EXPECT_FALSE(make_linear_solver("cholmod")->set_fixed_iterations(3));
}

// K - sigma I with sigma inside the spectrum: symmetric indefinite.
TEST(Krylov, IndefiniteMatrixBreaksCgButNotCrMinresGmres) {
  SparseMatrix A = stiffness();
  const Eigen::MatrixXd D(A);
  const Eigen::VectorXd eig = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(D, Eigen::EigenvaluesOnly).eigenvalues();
  const double sigma = 0.5 * (eig[10] + eig[11]);  // between the 11th and 12th eigenvalue: 11 negative
  for (Eigen::Index i = 0; i < A.rows(); ++i) A.coeffRef(i, i) -= sigma;
  const Eigen::VectorXd b = rhs(A.rows());
  KrylovOptions opt;
  opt.rtol = 1e-8;
  opt.max_iterations = 20000;
  // Restarted GMRES(m) can stagnate on symmetric indefinite systems: with m = 50
  // it stalls at a relative residual of 6.5e-3 here. A restart length of 300 (about
  // half the unknowns) keeps enough of the Krylov space; CR and MINRES need none.
  opt.restart = 300;
  const auto M = make_preconditioner("none");
  M->setup(A);
  Eigen::VectorXd x;
  const KrylovResult cg = conjugate_gradient(A, b, x, *M, opt);
  EXPECT_FALSE(cg.converged);
  EXPECT_NE(cg.breakdown.find("not positive definite"), std::string::npos) << cg.breakdown;
  using Method = KrylovResult (*)(const SparseMatrix&, const Eigen::VectorXd&, Eigen::VectorXd&,
                                  const Preconditioner&, const KrylovOptions&);
  const Method cr_method = &conjugate_residual, minres_method = &minres, gmres_method = &gmres;
  for (const Method method : {cr_method, minres_method, gmres_method}) {
    x.setZero(b.size());
    const KrylovResult r = (*method)(A, b, x, *M, opt);
    EXPECT_TRUE(r.converged) << "method " << (method == cr_method ? "cr" : method == minres_method ? "minres" : "gmres") << " " << r.breakdown << " residual " << r.relative_residual << " iterations " << r.iterations;
    EXPECT_LE((b - A * x).norm() / b.norm(), opt.rtol);
  }
  // Jacobi needs a positive diagonal: refused with a reason, not applied.
  SparseMatrix neg = A;
  neg.coeffRef(0, 0) = -1.0;
  const auto J = make_preconditioner("jacobi");
  EXPECT_FALSE(J->setup(neg));
  EXPECT_NE(J->last_error().find("diagonal entry 0"), std::string::npos);
}

// M^-1 as a dense matrix from its action on unit vectors: symmetric (to
// rounding of the triangular solves) and positive definite, as CG needs.
TEST(Preconditioners, AreSymmetricPositiveDefiniteOnSpdMatrices) {
  const SparseMatrix K = stiffness();
  for (const std::string& name : serial_preconditioners()) {
    const auto M = make_preconditioner(name);
    M->set_mesh_view(bar().mesh_view());
    ASSERT_TRUE(M->setup(K)) << name << ": " << M->last_error();
    const Eigen::MatrixXd Minv = dense_inverse(*M, K.rows());
    EXPECT_LE((Minv - Minv.transpose()).cwiseAbs().maxCoeff(), 1e-12 * Minv.cwiseAbs().maxCoeff()) << name;
    const Eigen::MatrixXd S = 0.5 * (Minv + Minv.transpose());
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(S, Eigen::EigenvaluesOnly).eigenvalues().minCoeff(), 0.0) << name;
  }
  EXPECT_THROW(make_preconditioner("amg-magic"), std::invalid_argument);
  EXPECT_THROW(make_linear_solver("cg+magic"), std::invalid_argument);
  EXPECT_THROW(make_linear_solver("bicgstab+jacobi"), std::invalid_argument);
}

// Jacobi is diag(K)^-1 and block Jacobi the inverses of K's 3x3 nodal blocks,
// entry by entry, against the blocks read off the dense K and inverted by
// Eigen's LU: a fault that still leaves an SPD preconditioner (1/sqrt(a_ii), a
// block's off-diagonals dropped) passes the test above and every Krylov
// solve, only slower. Measured: Jacobi exact, block Jacobi 3.9e-16 of the
// largest entry (the 3x3 inversions' round-off); 1e-12 is far above that and
// far below a wrong entry (the blocks' off-diagonal part alone is 0.35 of it).
TEST(Preconditioners, JacobiAndBlockJacobiInvertTheirPartOfTheMatrix) {
  const SparseMatrix K = stiffness();
  const Eigen::MatrixXd Kd = Eigen::MatrixXd(K);
  const Eigen::Index n = K.rows();
  ASSERT_EQ(n % 3, 0);
  Eigen::MatrixXd jacobi = Eigen::MatrixXd::Zero(n, n), block = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index i = 0; i < n; ++i) jacobi(i, i) = 1.0 / Kd(i, i);
  for (Eigen::Index b = 0; b < n; b += 3) block.block<3, 3>(b, b) = Kd.block<3, 3>(b, b).inverse();
  ASSERT_GT((block - jacobi).cwiseAbs().maxCoeff(), 0.1 * jacobi.cwiseAbs().maxCoeff());  // the blocks couple
  for (const auto& [name, expected] : {std::pair<std::string, const Eigen::MatrixXd*>{"jacobi", &jacobi},
                                       std::pair<std::string, const Eigen::MatrixXd*>{"block-jacobi", &block}}) {
    const auto M = make_preconditioner(name);
    ASSERT_TRUE(M->setup(K)) << name << ": " << M->last_error();
    const Eigen::MatrixXd Minv = dense_inverse(*M, n);
    EXPECT_LE((Minv - *expected).cwiseAbs().maxCoeff(), 1e-12 * expected->cwiseAbs().maxCoeff()) << name;
  }
}

// The direct solvers agree with each other; UMFPACK also solves the indefinite
// system Cholesky refuses.
TEST(DirectSolvers, UmfpackAndEigenLdltAgreeWithCholmod) {
  const SparseMatrix K = stiffness();
  const Eigen::VectorXd b = rhs(K.rows());
  Eigen::VectorXd x_ref, x;
  auto chol = make_linear_solver("cholmod");
  ASSERT_TRUE(chol->factorize(K));
  chol->solve(b, x_ref);
  for (const char* name : {"umfpack", "eigen-ldlt"}) {
    auto s = make_linear_solver(name);
    ASSERT_TRUE(s->factorize(K)) << name;
    ASSERT_TRUE(s->factorize(K)) << name;  // refactorisation reuses the symbolic analysis
    EXPECT_EQ(s->analyses(), 1) << name;
    s->solve(b, x);
    // Both backward stable: cond(K) ~1e4 times eps bounds the difference at ~1e-12.
    EXPECT_LE((x - x_ref).norm() / x_ref.norm(), 1e-10) << name;
  }
  // K - sigma I with sigma between the 11th and 12th eigenvalue: indefinite, nonsingular.
  const Eigen::MatrixXd D(K);
  const Eigen::VectorXd eig = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(D, Eigen::EigenvaluesOnly).eigenvalues();
  SparseMatrix A = K;
  for (Eigen::Index i = 0; i < A.rows(); ++i) A.coeffRef(i, i) -= 0.5 * (eig[10] + eig[11]);
  EXPECT_FALSE(chol->factorize(A));  // Cholesky refuses
  auto lu = make_linear_solver("umfpack");
  ASSERT_TRUE(lu->factorize(A));
  lu->solve(b, x);
  EXPECT_LE((b - A * x).norm() / b.norm(), 1e-10);  // backward stable LU
}

// CHOLMOD factors small matrices by a simplicial LDL^T, which completes on
// indefinite matrices; factorize() must still report them as not positive
// definite (Newton relies on it to project the Hessian).
TEST(DirectSolvers, CholmodRefusesSmallIndefiniteMatrices) {
  std::vector<Eigen::Triplet<double, std::int64_t>> t;
  for (int i = 0; i < 6; ++i) t.emplace_back(i, i, i == 3 ? -1.0 : 2.0);
  for (int i = 0; i + 1 < 6; ++i) t.emplace_back(i, i + 1, 0.5), t.emplace_back(i + 1, i, 0.5);
  SparseMatrix A(6, 6);
  A.setFromTriplets(t.begin(), t.end());
  auto chol = make_linear_solver("cholmod");
  EXPECT_FALSE(chol->factorize(A));
  A.coeffRef(3, 3) = 2.0;  // now diagonally dominant: SPD
  EXPECT_TRUE(chol->factorize(A));
}

// The direct solvers give OpenBLAS's threads only to factorisations big enough
// to pay for them (linalg/blas_threads.hpp): the bar's (~1e7 flops) runs on one
// thread, so no BLAS worker is left spinning beside the OpenMP loops that
// follow; a call of kThreadedBlasMinFlops gets the pool.
TEST(DirectSolvers, BlasThreadsOnlyForLargeFactorisations) {
  const int pool = use_blas_threads_for(kThreadedBlasMinFlops);
  EXPECT_EQ(openblas_get_num_threads(), pool);
  EXPECT_GE(pool, 1);
  EXPECT_LE(pool, omp_get_max_threads());
  const SparseMatrix K = stiffness();
  const Eigen::VectorXd b = rhs(K.rows());
  for (const char* name : {"cholmod", "umfpack"}) {
    use_blas_threads_for(kThreadedBlasMinFlops);
    auto s = make_linear_solver(name);
    ASSERT_TRUE(s->factorize(K)) << name;
    EXPECT_EQ(openblas_get_num_threads(), 1) << name;
    use_blas_threads_for(kThreadedBlasMinFlops);
    Eigen::VectorXd x;
    s->solve(b, x);
    EXPECT_EQ(openblas_get_num_threads(), 1) << name;
    EXPECT_LE((b - K * x).norm() / b.norm(), 1e-10) << name;  // backward stable, cond ~1e4
  }
  EXPECT_EQ(use_blas_threads_for(0.5 * kThreadedBlasMinFlops), 1);
}

// A matrix of the same size with a new pattern (two far-apart DOFs coupled, as a
// contact or a changed constraint would do) makes every direct solver analyse
// again instead of factorising against a stale ordering and structure.
TEST(DirectSolvers, AnalyseAgainWhenThePatternChanges) {
  const SparseMatrix K = stiffness();
  const Eigen::Index i = 0, j = K.rows() - 1;
  ASSERT_EQ(K.coeff(i, j), 0.0);  // not coupled in K
  // + eps (e_i + e_j)(e_i + e_j)^T keeps the matrix SPD and adds entries (i, j), (j, i).
  std::vector<Eigen::Triplet<double, std::int64_t>> t{{i, i, 1e-3}, {j, j, 1e-3}, {i, j, 1e-3}, {j, i, 1e-3}};
  SparseMatrix E(K.rows(), K.cols());
  E.setFromTriplets(t.begin(), t.end());
  SparseMatrix A = K + E;
  A.makeCompressed();
  const Eigen::VectorXd b = rhs(K.rows());
  for (const char* name : {"cholmod", "umfpack", "eigen-ldlt"}) {
    auto s = make_linear_solver(name);
    ASSERT_TRUE(s->factorize(K)) << name;
    ASSERT_TRUE(s->factorize(K)) << name;
    EXPECT_EQ(s->analyses(), 1) << name;  // same pattern: analysis reused
    ASSERT_TRUE(s->factorize(A)) << name;
    EXPECT_EQ(s->analyses(), 2) << name;
    Eigen::VectorXd x;
    s->solve(b, x);
    EXPECT_LE((b - A * x).norm() / b.norm(), 1e-10) << name;  // backward stable, cond ~1e4
  }
}

// Newton and the static problem run unchanged on an iterative solver: the
// manufactured-solution cube gives the same discrete solution as with CHOLMOD.
TEST(Krylov, DrivesTheStaticSolverThroughTheLinearSolverInterface) {
  const Mesh m = box_mesh(unit_cube(3), CellType::Tetrahedron, 2);
  const auto ref = verification::solve_pulled_neohookean(m, "cholmod");
  const auto it = verification::solve_pulled_neohookean(m, "minres+block-jacobi");
  ASSERT_TRUE(ref.converged && it.converged) << ref.message << " / " << it.message;
  // Both Newton solves stop at |g| <= 1e-10 of the load; the solutions then agree
  // to ~cond(K) * 1e-10 relative (cond ~1e3 for this mesh).
  EXPECT_LE((ref.displacement - it.displacement).norm() / ref.displacement.norm(), 1e-6);
}

}  // namespace
}  // namespace hofem

namespace hofem {
namespace {

// Inexact Newton (Eisenstat-Walker forcing terms): the same Newton stopping rule
// is met, the solution agrees with the exact-solve run, and the Krylov solver
// does less work because early Newton steps are solved loosely.
TEST(Newton, EisenstatWalkerForcingTermsCutLinearIterations) {
  const Mesh m = box_mesh(unit_cube(3), CellType::Tetrahedron, 2);
  const auto mat = make_material("neohookean", LameParameters::from_young_poisson(1.0, 0.3));
  const VectorField pull = [](const Eigen::Vector3d& X) { return Eigen::Vector3d(0.3 * X.x(), 0.05 * X.y(), 0.0); };
  StaticReport reports[2];
  Eigen::VectorXd u[2];
  for (int k = 0; k < 2; ++k) {
    StaticOptions opt;
    opt.solver = SolverSpec::parse("cg+block-jacobi");
    opt.newton.rtol = 1e-10;
    opt.newton.eisenstat_walker = (k == 1);
    StaticElasticity p(m, *mat, {{m.node_set("xmin"), nullptr}, {m.node_set("xmax"), pull}}, nullptr, opt);
    reports[k] = p.solve();
    ASSERT_TRUE(reports[k].converged) << reports[k].message;
    u[k] = p.displacement();
  }
  // Same stopping rule |g| <= 1e-10 of the force scale for both: solutions agree
  // to ~cond(K) * 1e-10 (cond ~1e3 here).
  EXPECT_LE((u[0] - u[1]).norm() / u[0].norm(), 1e-6);
  EXPECT_LT(reports[1].linear_iterations, reports[0].linear_iterations);
  // The forcing terms start loose (eta_max) and tighten as |g| falls.
  const auto& h = reports[1].steps.back().history;
  ASSERT_GE(h.size(), 2u);
  EXPECT_GT(h.front().linear_rtol, h.back().linear_rtol);
  std::cout << "linear iterations: exact " << reports[0].linear_iterations << " (" << reports[0].newton_iterations
            << " Newton), Eisenstat-Walker " << reports[1].linear_iterations << " (" << reports[1].newton_iterations
            << " Newton)\n";
}

}  // namespace
}  // namespace hofem
