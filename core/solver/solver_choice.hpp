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
//  - finite cells (embedded): CHOLMOD. The p-multigrid works there (the twisting
//    Hex20 finite-cell cylinder on an 8 x 8 x 12 grid, 15 implicit steps, 33
//    Newton iterations each way, one thread: CG + pmg 103 iterations per solve,
//    33.4 s; CG + Schwarz 247, 20.6 s; CG + Jacobi 1097, 37.9 s; CHOLMOD 21.1 s),
//    but cut cells with small volume fractions cost it iterations a conforming
//    mesh does not, and at these sizes CHOLMOD is as fast as the best of them.
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
/// spec's iteration budget and distributed options.
SolverChoice resolve_linear_solver(const SolverSpec& spec, const SystemTraits& traits);

}  // namespace hofem
