#pragma once
// Manufactured-solution convergence studies: error tables and observed
// rates on the finest pair of each sequence, asserted against the theoretical
// rates L2 >= p + 1 - 0.15 and H1 >= p - 0.15.
#include "study/convergence_table.hpp"
#include "study/manufactured_solution.hpp"
#include "report.hpp"

#include <string>
#include <vector>

namespace hofem::verification {

struct ConvergenceSeries {
  std::string problem;  ///< linear | neohookean
  CellType cell;
  int order;
  bool perturbed;
  std::vector<int> sizes;  ///< n (cubes per side), increasing
};

/// "ci": sizes chosen so the whole study runs in about a minute on 2 cores;
/// "full": the sequences n = 2, 4, 8, 16 (order 1 also 32), ~20 min.
std::vector<ConvergenceSeries> convergence_series(const std::string& preset);

/// Runs every series; adds one measurement per run (errors, DOFs, seconds) and
/// one check per observed rate; with `table`, also one row per run to it (the
/// tidy table `hofem verify` writes beside its report).
void add_convergence_checks(Report& report, const std::string& preset, ConvergenceTable* table = nullptr);

}  // namespace hofem::verification
