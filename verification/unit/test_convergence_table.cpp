// The convergence table (core/study/convergence_table.hpp) on runs with known
// errors: rates against the previous row of the same series only, none for a
// series' first row, and the CSV / JSON forms of the same rows.
#include "study/convergence_table.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

namespace hofem {
namespace {

// A run of order p on n cubes per side whose errors follow C h^(p+1) and C h^p
// exactly, so the observed rates are p + 1 and p up to the rounding of the logs.
MmsResult run_with_exact_rates(int order, int n) {
  MmsResult r;
  r.h = 1.0 / n;
  r.dofs = 3 * (order * n - 1) * (order * n - 1) * (order * n - 1);
  r.l2_error = 0.3 * std::pow(r.h, order + 1);
  r.h1_error = 0.7 * std::pow(r.h, order);
  r.linear_solver = "cg+pmg";
  r.converged = true;
  return r;
}

MmsCase case_of(const std::string& problem, int order, int n, bool perturbed = false) {
  MmsCase c;
  c.problem = problem;
  c.order = order;
  c.n = n;
  c.perturbed = perturbed;
  return c;
}

// Rates of errors C h^q come out as q up to two logarithms' rounding (~1e-15
// relative); 1e-12 allows that and no modelling slack.
constexpr double kRateTolerance = 1e-12;

TEST(ConvergenceTable, RatesAgainstThePreviousRowOfTheSameSeries) {
  ConvergenceTable table;
  // Series interleaved: order 1 and order 2 of the linear problem, and a
  // perturbed order 1, added in turns; each row's rate must ignore the others.
  for (int n : {2, 4, 8}) {
    for (int order : {1, 2}) table.add(case_of("linear", order, n), run_with_exact_rates(order, n));
    table.add(case_of("linear", 1, n, true), run_with_exact_rates(1, n));
  }
  ASSERT_EQ(table.rows().size(), 9u);
  for (const ConvergenceRow& row : table.rows()) {
    if (row.n == 2) {
      EXPECT_FALSE(row.rate_l2.has_value()) << row.mesh << " p" << row.order;
      EXPECT_FALSE(row.rate_h1.has_value());
      continue;
    }
    ASSERT_TRUE(row.rate_l2 && row.rate_h1);
    EXPECT_NEAR(*row.rate_l2, row.order + 1, kRateTolerance) << row.mesh << " p" << row.order << " n" << row.n;
    EXPECT_NEAR(*row.rate_h1, row.order, kRateTolerance);
  }
}

TEST(ConvergenceTable, ObservedRateIsTheLogLogSlope) {
  // Halving h divides an O(h^3) error by 8: rate 3. Errors 1e-2 -> 1e-3 over
  // h 0.1 -> 0.01: rate 1.
  EXPECT_NEAR(observed_rate(8.0, 1.0, 0.5, 0.25), 3.0, kRateTolerance);
  EXPECT_NEAR(observed_rate(1e-2, 1e-3, 0.1, 0.01), 1.0, kRateTolerance);
}

TEST(ConvergenceTable, CsvHasTheHeaderAndEmptyFirstRates) {
  ConvergenceTable table;
  table.add(case_of("neohookean", 2, 2), run_with_exact_rates(2, 2));
  table.add(case_of("neohookean", 2, 4), run_with_exact_rates(2, 4));
  std::istringstream csv(table.to_csv());
  std::string header, first, second, extra;
  std::getline(csv, header);
  std::getline(csv, first);
  std::getline(csv, second);
  EXPECT_FALSE(std::getline(csv, extra)) << "one line per row after the header";
  EXPECT_EQ(header,
            "problem,cell,order,mesh,n,h,unknowns,cells,l2_error,h1_error,rate_l2,rate_h1,setup_seconds,"
            "assembly_seconds,solve_seconds,total_seconds,newton_iterations,linear_iterations,linear_solver,converged");
  // neohookean,tet,2,uniform,2,0.5,27,0,<l2>,<h1>,,,... : the 11th and 12th fields empty.
  EXPECT_EQ(first.rfind("neohookean,tet,2,uniform,2,0.5,81,0,", 0), 0u) << first;
  EXPECT_NE(first.find(",,,"), std::string::npos) << first;
  EXPECT_EQ(second.find(",,"), std::string::npos) << "the second row has both rates: " << second;
}

TEST(ConvergenceTable, JsonDescribesEveryColumnAndNullsTheFirstRates) {
  ConvergenceTable table;
  table.add(case_of("linear", 3, 2), run_with_exact_rates(3, 2));
  table.add(case_of("linear", 3, 4), run_with_exact_rates(3, 4));
  const nlohmann::json j = table.to_json();
  ASSERT_EQ(j["columns"].size(), 20u);
  for (const auto& c : j["columns"]) {
    EXPECT_FALSE(c["unit"].get<std::string>().empty()) << c.dump();
    EXPECT_FALSE(c["description"].get<std::string>().empty()) << c.dump();
    EXPECT_TRUE(j["rows"][0].contains(c["name"].get<std::string>())) << c.dump();
  }
  EXPECT_TRUE(j["rows"][0]["rate_l2"].is_null());
  EXPECT_NEAR(j["rows"][1]["rate_l2"].get<double>(), 4.0, kRateTolerance);
  EXPECT_EQ(j["rows"][1]["unknowns"].get<int>(), 3 * 11 * 11 * 11);
}

}  // namespace
}  // namespace hofem
