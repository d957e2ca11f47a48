#pragma once
// The linear solver "auto" stands for: the fastest one measured on this kind of
// system. The rules and the measurements behind them (2 cores, the
// manufactured-solution cube of `hofem mms`, assembly + set-up + solve; the full
// tables are in DEVELOPERS.md's solver section and reports/time_to_error.json):
//
//  - order >= 2, conforming mesh: CG + p-multigrid. It beat CHOLMOD at every size
//    run, from P3 n = 2 (0.00 vs 0.01 s) to P3 n = 12 (1.6 vs 8.0 s), with
//    iterations flat in n (10-13 at rtol 1e-10), and is SPD for every Hessian
//    Newton hands it (Newton projects an indefinite one, as for any CG).
//  - order 1: no coarser p level. CHOLMOD below 30,000 free unknowns (P1 n = 16,
//    14k unknowns: 0.37 s direct vs 0.46 s CG + BoomerAMG, whose set-up costs
//    ~0.3 s at any size), CG + BoomerAMG above (P1 n = 24, 45k: 1.34 vs 1.12 s).
//  - finite cells (embedded), order >= 2: CG + p-multigrid whose fine-level
//    smoother takes the cut cells' Schwarz blocks (p_multigrid.hpp), CHOLMOD
//    below kEmbeddedDirectLimit unknowns. Before the blocks the p-multigrid
//    needed 2.6x the iterations on cut cells (Hex20 twisting cylinder, 29 k
//    unknowns, nu = 0.48: 1343 against 517 CG iterations over 9 Newton solves)
//    and CHOLMOD was the choice at every size. The limit is fitted to
//    BM_ImplicitStep (benchmarks/bench_implicit_step.cpp).
//  - finite cells of order 1 (a Hex8 background) follow the order-1 rule.
//  - "auto" reuses preconditioner set-ups across Newton iterations and time
//    steps by the amortised rule (SetupReuse, linalg/krylov.cpp); a named
//    solver sets up every matrix unless its spec says otherwise.
//  - distributed runs do not ask: they always solve on hypre.
#include "solver/solver_spec.hpp"

#include <Eigen/Core>

#include <string>

namespace hofem {

/// What the choice depends on.
struct SystemTraits {
  Eigen::Index free_dofs = 0;
  int order = 1;
  bool embedded = false;  ///< finite-cell (cut-cell) element rules
};

struct SolverChoice {
  SolverSpec spec;     ///< resolved: a method, never "auto"
  std::string reason;  ///< one line, for logs and reports
};

/// The rules above.
SolverChoice choose_linear_solver(const SystemTraits& traits);

/// `spec` itself ("given"), or for "auto" the choice for `traits`, keeping the
/// spec's iteration budget, Krylov options (set-up reuse) and distributed options.
SolverChoice resolve_linear_solver(const SolverSpec& spec, const SystemTraits& traits);

}  // namespace hofem
