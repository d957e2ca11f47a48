#include "solver/solver_choice.hpp"

#include <fmt/format.h>

namespace hofem {

namespace {
// Order 1: CHOLMOD up to here, CG + BoomerAMG above (the crossover measured in the header).
constexpr Eigen::Index kOrderOneDirectLimit = 30000;
// Finite cells of order >= 2: CHOLMOD up to here, CG + p-multigrid above (BM_ImplicitStep, the header).
constexpr Eigen::Index kEmbeddedDirectLimit = 10000;
}  // namespace

SolverChoice choose_linear_solver(const SystemTraits& t) {
  if (t.embedded && t.order >= 2 && t.free_dofs <= kEmbeddedDirectLimit)
    return {SolverSpec::parse("cholmod"), fmt::format("finite cells, {} <= {} unknowns: direct", t.free_dofs,
                                                      kEmbeddedDirectLimit)};
  if (t.embedded && t.order >= 2)
    return {SolverSpec::parse("cg+pmg"), fmt::format("finite cells, order {} ({} unknowns): p-multigrid with the cut "
                                                     "cells' Schwarz blocks in its smoother",
                                                     t.order, t.free_dofs)};
  if (t.order >= 2)
    return {SolverSpec::parse("cg+pmg"), fmt::format("order {} ({} unknowns): p-multigrid, iterations independent of the mesh", t.order,
                                  t.free_dofs)};
  if (t.free_dofs <= kOrderOneDirectLimit)
    return {SolverSpec::parse("cholmod"), fmt::format("order 1, {} <= {} unknowns: direct is faster than AMG's set-up", t.free_dofs,
                                   kOrderOneDirectLimit)};
  return {SolverSpec::parse("cg+amg"), fmt::format("order 1, {} > {} unknowns: algebraic multigrid", t.free_dofs, kOrderOneDirectLimit)};
}

SolverChoice resolve_linear_solver(const SolverSpec& spec, const SystemTraits& traits) {
  if (!spec.is_auto()) return {spec, "given"};
  SolverChoice choice = choose_linear_solver(traits);
  choice.spec.fixed_iterations = spec.fixed_iterations;
  choice.spec.krylov = spec.krylov;
  // "auto" reuses set-ups by the amortised rule (krylov.cpp) unless told otherwise.
  if (choice.spec.krylov.setup_reuse == SetupReuse::Default) choice.spec.krylov.setup_reuse = SetupReuse::Amortised;
  choice.spec.distributed = spec.distributed;
  return choice;
}

}  // namespace hofem
