#pragma once
// One row per check: what was measured, the threshold it is held to, and the
// verdict. Rows are grouped ("quadrature.exactness", "basis.kronecker", ...);
// the report serialises to reports/verification.json.
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace hofem::verification {

enum class Compare { AtMost, AtLeast };

struct CheckRow {
  std::string group;      ///< e.g. "quadrature.exactness"
  std::string name;       ///< what was checked, e.g. "tet WV15-8-46"
  double measured = 0.0;  ///< the measured value
  double threshold = 0.0; ///< the bound it is held to
  Compare compare = Compare::AtMost;
  bool pass = false;
  std::string why;        ///< justification of the threshold / extra facts
};

class Report {
 public:
  /// Adds a row; pass = measured <= threshold (AtMost) or >= (AtLeast). NaN fails.
  /// `why` justifies the threshold: an empty one throws std::invalid_argument
  /// (naming the group and the row), so that no row can go unexplained.
  const CheckRow& check(std::string group, std::string name, double measured, double threshold, Compare compare,
                        std::string why);
  /// An observed convergence rate held from both sides: a row `>= expected - below`
  /// and a row of the same name `<= expected + above`. A rate above the window is
  /// as much a defect as one below it: the error is measured in another norm than
  /// the one the theory bounds, or the exact solution lies in the discrete space
  /// (the error is round-off and its "rate" noise). `why` justifies both bounds.
  void check_rate(const std::string& group, const std::string& name, double observed, double expected, double below,
                  double above, const std::string& why);
  /// Records a measured fact that has no pass/fail verdict (e.g. the condition
  /// number of the thesis' monomial Vandermonde, shown beside a checked quantity).
  void measure(std::string group, std::string name, double value, std::string what = {});
  const std::vector<CheckRow>& rows() const { return rows_; }
  int failures() const;
  nlohmann::json to_json() const;
  /// The rows and measurements whose group starts with `prefix` (a report of its own:
  /// its summary counts only those).
  Report only(const std::string& prefix) const;
  /// Short per-group table (rows, failures, worst margin) for terminals.
  std::string summary_table() const;

 private:
  std::vector<CheckRow> rows_;
  struct Measurement {
    std::string group, name, what;
    double value;
  };
  std::vector<Measurement> measurements_;
};

}  // namespace hofem::verification
