// The rule behind the linear solver "auto" (solver/solver_choice.hpp), at the
// edges of its cases, and what "auto" resolves the set-up reuse to.
#include "solver/solver_choice.hpp"

#include <gtest/gtest.h>

namespace hofem {
namespace {

std::string chosen(Eigen::Index n, int order, bool embedded) {
  return choose_linear_solver({n, order, embedded}).spec.name();
}

TEST(SolverChoice, ConformingHighOrderIsPMultigridAtEverySize) {
  for (Eigen::Index n : {Eigen::Index(30), Eigen::Index(30000), Eigen::Index(4000000)})
    for (int order : {2, 3, 4}) EXPECT_EQ(chosen(n, order, false), "cg+pmg") << n << " unknowns, order " << order;
}

TEST(SolverChoice, OrderOneIsDirectUpToItsLimitThenAmg) {
  EXPECT_EQ(chosen(30000, 1, false), "cholmod");
  EXPECT_EQ(chosen(30001, 1, false), "cg+amg");
  // A finite-cell Hex8 background follows the order-1 rule.
  EXPECT_EQ(chosen(30000, 1, true), "cholmod");
  EXPECT_EQ(chosen(30001, 1, true), "cg+amg");
}

TEST(SolverChoice, FiniteCellsOfHigherOrderAreDirectWhenSmallThenPMultigrid) {
  EXPECT_EQ(chosen(10000, 2, true), "cholmod");
  EXPECT_EQ(chosen(10001, 2, true), "cg+pmg");
  EXPECT_NE(choose_linear_solver({10001, 2, true}).reason.find("Schwarz"), std::string::npos)
      << "the reason names the cut-cell blocks the smoother takes";
}

TEST(SolverChoice, AutoReusesSetupsByTheAmortisedRuleANamedSolverDoesNot) {
  const SolverChoice a = resolve_linear_solver(SolverSpec::parse("auto"), {100000, 2, false});
  EXPECT_EQ(a.spec.krylov.setup_reuse, SetupReuse::Amortised);
  const SolverChoice named = resolve_linear_solver(SolverSpec::parse("cg+pmg"), {100000, 2, false});
  EXPECT_EQ(named.reason, "given");
  EXPECT_EQ(named.spec.krylov.setup_reuse, SetupReuse::Default);  // KrylovSolver reads Default as Never
  SolverSpec never = SolverSpec::parse("auto");
  never.krylov.setup_reuse = SetupReuse::Never;
  EXPECT_EQ(resolve_linear_solver(never, {100000, 2, false}).spec.krylov.setup_reuse, SetupReuse::Never);
  // The spec's fixed budget survives the resolution.
  SolverSpec budget = SolverSpec::parse("auto");
  budget.fixed_iterations = 7;
  EXPECT_EQ(resolve_linear_solver(budget, {100000, 2, false}).spec.fixed_iterations, 7);
}

}  // namespace
}  // namespace hofem
