// Preconditioner set-up reuse in KrylovSolver (KrylovOptions::setup_reuse):
// the policies of krylov.cpp on matrices whose stale set-ups cost a known amount.
#include "elastic_test_systems.hpp"
#include "mesh/box_mesh.hpp"
#include "linalg/krylov.hpp"
#include "solver/solver_factory.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace hofem {
namespace {

using verification::ClampedElasticBody;

// A P2 tetrahedral bar clamped at x = 0, ~600 unknowns.
const ClampedElasticBody& bar() {
  static const ClampedElasticBody system(box_mesh(BoxSpec{{0, 0, 0}, {2, 1, 1}, {4, 2, 2}}, CellType::Tetrahedron, 2));
  return system;
}

// D K D with D = 1 on the first half of the unknowns and `s` on the second: a
// matrix of K's pattern on which K's Jacobi set-up is badly scaled (stale)
// while its own is as good as K's on K (Jacobi-PCG is invariant under a
// symmetric diagonal scaling).
SparseMatrix scaled(const SparseMatrix& K, double s) {
  Eigen::VectorXd d = Eigen::VectorXd::Ones(K.rows());
  d.tail(K.rows() / 2).setConstant(s);
  SparseMatrix out = d.asDiagonal() * K * d.asDiagonal();
  out.makeCompressed();
  return out;
}

int solve(KrylovSolver& s, const SparseMatrix& A, Eigen::VectorXd& x) {
  EXPECT_TRUE(s.factorize(A));
  const Eigen::VectorXd b = verification::smooth_rhs(A.rows());
  s.solve(b, x);
  // Whatever set-up the preconditioner has, the answer is A's: the relative
  // residual meets the solver's tolerance (1e-10 below) with A, not with an
  // older matrix.
  EXPECT_LE((b - A * x).norm() / b.norm(), 1e-10) << s.name();
  return s.last_iterations();
}

// growth 0: SetupReuse::Never; else SetupReuse::Growth with that factor.
KrylovOptions options(double growth) {
  KrylovOptions o;
  o.rtol = 1e-10;
  o.setup_reuse = growth > 0.0 ? SetupReuse::Growth : SetupReuse::Never;
  o.setup_reuse_growth = growth;
  return o;
}

TEST(SetupReuse, OffMeansASetupPerMatrix) {
  KrylovSolver s(SolverMethod::Cg, make_preconditioner("jacobi"), options(0.0));
  Eigen::VectorXd x;
  for (int k = 0; k < 3; ++k) solve(s, bar().K, x);
  EXPECT_EQ(s.factorizations(), 3);
  EXPECT_EQ(s.setup_reuses(), 0);
}

// The same matrix again: the set-up is reused and costs no iteration more.
TEST(SetupReuse, SameMatrixReusesTheSetup) {
  KrylovSolver s(SolverMethod::Cg, make_preconditioner("jacobi"), options(1.5));
  Eigen::VectorXd x;
  const int first = solve(s, bar().K, x);
  const int second = solve(s, bar().K, x);
  EXPECT_EQ(s.factorizations(), 1);
  EXPECT_EQ(s.setup_reuses(), 1);
  EXPECT_EQ(second, first);
}

// A matrix on which the stale set-up needs more than growth x the iterations
// of the solve after the set-up: that solve is still answered (on the stale
// preconditioner, within max_iterations), and the next matrix gets a new set-up.
TEST(SetupReuse, IterationGrowthPastTheFactorTriggersANewSetup) {
  KrylovSolver s(SolverMethod::Cg, make_preconditioner("jacobi"), options(1.5));
  Eigen::VectorXd x;
  const int baseline = solve(s, bar().K, x);
  const SparseMatrix K2 = scaled(bar().K, 30.0);
  const int stale = solve(s, K2, x);
  EXPECT_EQ(s.setup_reuses(), 1);
  EXPECT_GT(stale, 1.5 * baseline) << "the stale set-up is not measurably worse: the test has no trigger";
  const int fresh = solve(s, K2, x);
  EXPECT_EQ(s.factorizations(), 2) << "growth past the factor must end the reuse";
  EXPECT_EQ(s.setup_reuses(), 1);
  EXPECT_LT(fresh, stale);
}

// A reused set-up under which the solve fails (here: the iteration limit
// between the fresh and the stale counts) is retried once on a fresh set-up,
// and the iterations reported are both attempts'.
TEST(SetupReuse, FailureOnAReusedSetupRetriesOnAFreshOne) {
  const SparseMatrix K2 = scaled(bar().K, 30.0);
  int base_k = 0, fresh_k2 = 0, stale_k2 = 0;
  {
    KrylovSolver probe(SolverMethod::Cg, make_preconditioner("jacobi"), options(1e6));
    Eigen::VectorXd x;
    base_k = solve(probe, bar().K, x);
    stale_k2 = solve(probe, K2, x);
    KrylovSolver fresh(SolverMethod::Cg, make_preconditioner("jacobi"), options(0.0));
    fresh_k2 = solve(fresh, K2, x);
  }
  KrylovOptions o = options(1e6);
  o.max_iterations = (std::max(base_k, fresh_k2) + stale_k2) / 2;
  ASSERT_GT(o.max_iterations, std::max(base_k, fresh_k2));
  ASSERT_LT(o.max_iterations, stale_k2);
  KrylovSolver s(SolverMethod::Cg, make_preconditioner("jacobi"), o);
  Eigen::VectorXd x;
  solve(s, bar().K, x);
  const int iterations = solve(s, K2, x);
  EXPECT_EQ(s.factorizations(), 2);
  EXPECT_EQ(s.setup_reuses(), 1);
  EXPECT_EQ(iterations, o.max_iterations + fresh_k2);
}

// Amortised: the same matrix costs no extra iteration, so a set-up is never
// worth making again (e_L = 0 never exceeds S / t + E >= 0).
TEST(SetupReuse, AmortisedKeepsASetupThatCostsNothing) {
  KrylovOptions o = options(0.0);
  o.setup_reuse = SetupReuse::Amortised;
  KrylovSolver s(SolverMethod::Cg, make_preconditioner("jacobi"), o);
  Eigen::VectorXd x;
  for (int k = 0; k < 5; ++k) solve(s, bar().K, x);
  EXPECT_EQ(s.factorizations(), 1);
  EXPECT_EQ(s.setup_reuses(), 4);
}

// Amortised: a stale set-up that costs e extra iterations per solve, with a
// Jacobi set-up worth well under one iteration (S / t << 1: a diagonal
// inversion against a product and a preconditioner pass per iteration), is
// dropped after the second solve on it: e L = 2e > S / t + e once e > S / t.
TEST(SetupReuse, AmortisedRebuildsWhenTheStaleSolvesCostMoreThanTheSetup) {
  KrylovOptions o = options(0.0);
  o.setup_reuse = SetupReuse::Amortised;
  KrylovSolver s(SolverMethod::Cg, make_preconditioner("jacobi"), o);
  Eigen::VectorXd x;
  solve(s, bar().K, x);
  const SparseMatrix K2 = scaled(bar().K, 30.0);
  solve(s, K2, x);  // stale, L = 2: e L = 2e vs S/t + e, rebuild_next once e > S/t
  EXPECT_EQ(s.factorizations(), 1);
  solve(s, K2, x);
  EXPECT_EQ(s.factorizations(), 2) << "a stale set-up costing many iterations must be replaced";
}

// A fixed iteration budget has no count to trigger on: no reuse.
TEST(SetupReuse, FixedIterationBudgetSetsUpEveryMatrix) {
  KrylovSolver s(SolverMethod::Cg, make_preconditioner("jacobi"), options(1.5));
  s.set_fixed_iterations(5);
  Eigen::VectorXd x;
  const Eigen::VectorXd b = verification::smooth_rhs(bar().K.rows());
  for (int k = 0; k < 3; ++k) {
    ASSERT_TRUE(s.factorize(bar().K));
    s.solve(b, x);
  }
  EXPECT_EQ(s.factorizations(), 3);
  EXPECT_EQ(s.setup_reuses(), 0);
}

}  // namespace
}  // namespace hofem
