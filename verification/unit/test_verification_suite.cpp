// The whole table-driven verification suite, as a test: any failing row fails,
// and the failing rows are printed with their measured values.
#include "run_verification.hpp"

#include <gtest/gtest.h>

namespace hofem::verification {
namespace {

// The fast part of the suite; the convergence study runs once, through the CLI
// test `cli.verify` (hofem verify --convergence ci), so it is not run twice.
TEST(VerificationSuite, EveryFastCheckPasses) {
  const Report report = run_fast_checks();
  EXPECT_GT(report.rows().size(), 1000u);
  for (const CheckRow& r : report.rows())
    EXPECT_TRUE(r.pass) << r.group << " | " << r.name << ": measured " << r.measured << ", threshold "
                        << (r.compare == Compare::AtMost ? "<= " : ">= ") << r.threshold;
  EXPECT_EQ(report.failures(), 0);
}

// The report machinery itself: a failing row is reported as failing, NaN fails,
// and the JSON summary counts it.
TEST(VerificationReport, CountsFailuresAndRejectsNaN) {
  Report r;
  r.check("g", "ok", 1.0, 2.0, Compare::AtMost);
  r.check("g", "too big", 3.0, 2.0, Compare::AtMost);
  r.check("g", "nan", std::nan(""), 2.0, Compare::AtMost);
  r.check("h", "at least", 1.0, 2.0, Compare::AtLeast);
  EXPECT_EQ(r.failures(), 3);
  const auto j = r.to_json();
  EXPECT_EQ(j["summary"]["failed"], 3);
  EXPECT_EQ(j["summary"]["groups"]["g"]["failed"], 2);
  EXPECT_TRUE(j["rows"][2]["measured"].is_string());
}

// `hofem verify --group P` writes Report::only(P): that prefix's rows and
// measurements, with a summary that counts only them.
TEST(VerificationReport, OnlyKeepsOneGroupPrefix) {
  Report r;
  r.check("partition.balance", "a", 0.0, 1.0, Compare::AtMost);
  r.check("partition.cut", "b", 2.0, 1.0, Compare::AtMost);
  r.check("quadrature.exactness", "c", 0.0, 1.0, Compare::AtMost);
  r.measure("partition.seconds", "t", 0.1);
  r.measure("embedded.fig4", "t", 0.2);
  const auto j = r.only("partition").to_json();
  EXPECT_EQ(j["rows"].size(), 2u);
  EXPECT_EQ(j["measurements"].size(), 1u);
  EXPECT_EQ(j["summary"]["checks"], 2);
  EXPECT_EQ(j["summary"]["failed"], 1);
  EXPECT_FALSE(j["summary"]["groups"].contains("quadrature.exactness"));
}

}  // namespace
}  // namespace hofem::verification
