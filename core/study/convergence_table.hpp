#pragma once
// The convergence table of manufactured-solution runs, in the tidy layout users
// know from deal.II's ConvergenceTable (tutorial step-7): one row per run, one
// column per quantity, the observed rates beside the errors. `hofem verify`
// writes it as CSV and JSON next to its report; `hofem mms` with lists of orders
// and sizes prints its rows. The JSON carries each column's unit and meaning.
//
// A series is the runs of one (problem, cell, order, mesh kind); a row's rates
// are against the row added before it in the same series (none for the first).
#include "study/manufactured_solution.hpp"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace hofem {

/// Observed order of convergence between two runs: the slope of log(error)
/// against log(h), log(e_coarse / e_fine) / log(h_coarse / h_fine).
double observed_rate(double error_coarse, double error_fine, double h_coarse, double h_fine);

struct ConvergenceRow {
  std::string problem;  ///< the material (material_names())
  std::string cell;     ///< tet | hex
  int order = 1;
  std::string mesh;  ///< uniform | perturbed
  int n = 0;         ///< cubes per side
  double h = 0.0;
  int unknowns = 0, cells = 0;
  double l2_error = 0.0, h1_error = 0.0;
  std::optional<double> rate_l2, rate_h1;  ///< empty for a series' first row
  double setup_seconds = 0.0, assembly_seconds = 0.0, solve_seconds = 0.0, total_seconds = 0.0;
  int newton_iterations = 0, linear_iterations = 0;
  std::string linear_solver;
  bool converged = false;
};

class ConvergenceTable {
 public:
  /// Appends the run of case `c`; returns its row with the rates against the
  /// previous row of its series.
  const ConvergenceRow& add(const MmsCase& c, const MmsResult& r);
  const std::vector<ConvergenceRow>& rows() const { return rows_; }

  /// Header line and one line per row; an absent rate is an empty field.
  std::string to_csv() const;
  /// {"columns": [{"name", "unit", "description"}...], "rows": [{name: value}...]}
  /// (absent rates are null).
  nlohmann::json to_json() const;
  /// One row as a JSON object keyed by column name.
  static nlohmann::json row_json(const ConvergenceRow& row);

 private:
  std::vector<ConvergenceRow> rows_;
};

}  // namespace hofem
