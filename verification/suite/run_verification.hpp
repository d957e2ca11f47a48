#pragma once
#include "report.hpp"
#include "study/convergence_table.hpp"

#include <string>

namespace hofem::verification {

struct SuiteOptions {
  /// Manufactured-solution convergence study: "none", "ci" or "full".
  std::string convergence = "ci";
  /// Linear solvers and preconditioners (solver_checks.hpp; starts MPI for BoomerAMG).
  bool solvers = true;
  /// If set, receives one row per run of the convergence study.
  ConvergenceTable* convergence_table = nullptr;
};

/// Fast checks: quadrature, bases, materials, elements, patch tests, partition quality (seconds).
Report run_fast_checks();

/// Every check of the suite: the fast ones, the solver checks and the convergence study.
Report run_all_checks(const SuiteOptions& options = {});

}  // namespace hofem::verification
