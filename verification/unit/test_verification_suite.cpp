// The verification suite's machinery: the table of families, the report and
// its JUnit form (the checks themselves run as ctest's verify.<id> tests).
#include "junit_report.hpp"
#include "run_verification.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace hofem::verification {
namespace {

// The families themselves run as ctest's verify.<id> tests (hofem verify
// --group ...); here, the table that selects them.
TEST(VerificationFamilies, GroupPrefixesSelectTheirFamilies) {
  const auto ids = [](const std::string& group, const std::string& convergence = "ci") {
    std::string out;
    for (const CheckFamily* f : selected_families({.convergence = convergence, .group = group}))
      out += (out.empty() ? "" : " ") + f->id;
    return out;
  };
  EXPECT_EQ(ids("quadrature"), "quadrature");
  EXPECT_EQ(ids("quadrature.exactness"), "quadrature");  // a group inside a family
  EXPECT_EQ(ids("embedded"), "fig4 loads setup fig5 fig6 fig10");
  EXPECT_EQ(ids("embedded", "none"), "fig4 loads setup");      // no convergence families
  EXPECT_EQ(ids("embedded.fig1"), "fig10");
  EXPECT_EQ(ids("mms.rate_h1"), "mms");
  EXPECT_EQ(ids("nosuch"), "");
  EXPECT_EQ(selected_families({.convergence = "ci"}).size(), check_families().size());
  EXPECT_EQ(selected_families({.convergence = "none"}).size(), 11u);  // the fast ten and the solvers
  EXPECT_NE(no_families_message({.group = "nosuch"}).find("groups start with: quadrature., basis."), std::string::npos);
}

// Every family's groups are distinct prefixes, so no two families claim a row.
TEST(VerificationFamilies, GroupsDoNotOverlap) {
  std::vector<std::string> all;
  for (const CheckFamily& f : check_families()) all.insert(all.end(), f.groups.begin(), f.groups.end());
  for (std::size_t i = 0; i < all.size(); ++i)
    for (std::size_t j = 0; j < all.size(); ++j)
      if (i != j) {
        EXPECT_FALSE(all[j].starts_with(all[i])) << all[i] << " is a prefix of " << all[j];
      }
}

// JUnit: a failing check becomes a <failure> with measured, threshold and why;
// passing ones are empty testcases; markup in names is escaped.
TEST(VerificationJunit, FailuresCarryMeasuredThresholdAndWhy) {
  Report r;
  r.check("quadrature.exactness", "tet <WV> & \"5\"", 1e-16, 1e-13, Compare::AtMost, "rounding");
  r.check("mms.rate_h1", "tet p2", 1.2, 1.9, Compare::AtLeast, "asymptotic rate p");
  const std::string xml = junit_xml(r, "hofem.verify");
  EXPECT_NE(xml.find("<testsuites name=\"hofem.verify\" tests=\"2\" failures=\"1\">"), std::string::npos) << xml;
  EXPECT_NE(xml.find("name=\"tet &lt;WV&gt; &amp; &quot;5&quot;\"/>"), std::string::npos) << xml;
  EXPECT_NE(xml.find("<failure message=\"measured 1.2, threshold &gt;= 1.9: asymptotic rate p\">"), std::string::npos)
      << xml;
  EXPECT_EQ(xml_escape(std::string("a\x01" "b\tc")), "a?b\tc");  // XML 1.0 holds no control characters
}

// The report machinery itself: a failing row is reported as failing, NaN fails,
// and the JSON summary counts it.
TEST(VerificationReport, CountsFailuresAndRejectsNaN) {
  Report r;
  r.check("g", "ok", 1.0, 2.0, Compare::AtMost, "test");
  r.check("g", "too big", 3.0, 2.0, Compare::AtMost, "test");
  r.check("g", "nan", std::nan(""), 2.0, Compare::AtMost, "test");
  r.check("h", "at least", 1.0, 2.0, Compare::AtLeast, "test");
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
  r.check("partition.balance", "a", 0.0, 1.0, Compare::AtMost, "test");
  r.check("partition.cut", "b", 2.0, 1.0, Compare::AtMost, "test");
  r.check("quadrature.exactness", "c", 0.0, 1.0, Compare::AtMost, "test");
  r.measure("partition.seconds", "t", 0.1);
  r.measure("embedded.fig4", "t", 0.2);
  const auto j = r.only("partition").to_json();
  EXPECT_EQ(j["rows"].size(), 2u);
  EXPECT_EQ(j["measurements"].size(), 1u);
  EXPECT_EQ(j["summary"]["checks"], 2);
  EXPECT_EQ(j["summary"]["failed"], 1);
  EXPECT_FALSE(j["summary"]["groups"].contains("quadrature.exactness"));
}

// Every row says why its threshold is what it is: a row without a reason is
// refused, naming the row, and adds nothing.
TEST(VerificationReport, RefusesARowWithoutWhy) {
  Report r;
  try {
    r.check("mms.converged", "linear|tet|p1", 0.5, 1.0, Compare::AtMost, "");
    FAIL() << "an empty why was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("mms.converged"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("linear|tet|p1"), std::string::npos) << e.what();
  }
  EXPECT_THROW(r.check_rate("mms.rate_l2", "p1", 2.0, 2.0, 0.15, 0.35, ""), std::invalid_argument);
  EXPECT_TRUE(r.rows().empty());
}

// A rate is held from both sides: two rows of the same name, >= expected - below
// and <= expected + above; too fast fails as much as too slow, and says where to look.
TEST(VerificationReport, CheckRateHoldsBothSides) {
  const auto rows_of = [](double observed) {
    Report r;
    r.check_rate("mms.rate_l2", "p3", observed, 4.0, 0.15, 0.35, "O(h^4)");
    return r.rows();
  };
  const std::vector<CheckRow> inside = rows_of(4.18);
  ASSERT_EQ(inside.size(), 2u);
  EXPECT_EQ(inside[0].name, inside[1].name);
  EXPECT_EQ(inside[0].compare, Compare::AtLeast);
  EXPECT_DOUBLE_EQ(inside[0].threshold, 3.85);
  EXPECT_EQ(inside[1].compare, Compare::AtMost);
  EXPECT_DOUBLE_EQ(inside[1].threshold, 4.35);
  EXPECT_TRUE(inside[0].pass && inside[1].pass);
  EXPECT_NE(inside[1].why.find("O(h^4)"), std::string::npos);

  const std::vector<CheckRow> fast = rows_of(5.0);  // e.g. an L2 error reported as H1
  EXPECT_TRUE(fast[0].pass);
  EXPECT_FALSE(fast[1].pass);
  EXPECT_TRUE(fast[1].why.starts_with("faster than theory: check the error norm")) << fast[1].why;

  const std::vector<CheckRow> slow = rows_of(3.5);
  EXPECT_FALSE(slow[0].pass);
  EXPECT_TRUE(slow[1].pass);

  const std::vector<CheckRow> nan = rows_of(std::nan(""));
  EXPECT_FALSE(nan[0].pass || nan[1].pass);
}

}  // namespace
}  // namespace hofem::verification
