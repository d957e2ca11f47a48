// The rule query and the published-rule data path (including malformed data).
#include "quadrature/published_rules.hpp"
#include "quadrature/rule_library.hpp"

#include <gtest/gtest.h>

#include <set>
#include <thread>

namespace hofem {
namespace {

TEST(RuleLibrary, EveryDegreeUpTo20HasATabulatedPositiveInteriorRule) {
  for (CellType cell : {CellType::Triangle, CellType::Tetrahedron}) {
    EXPECT_EQ(max_tabulated_degree(cell), 20);
    for (int d = 1; d <= 20; ++d) {
      bool found = false;
      for (const QuadratureRule& r : tabulated_rules(cell)) found = found || (r.degree == d && r.positive_interior());
      // Tet degree 4 has no rule of its own: the 14-point degree-5 rule is the fewest (WV15).
      if (!(cell == CellType::Tetrahedron && d == 4)) {
        EXPECT_TRUE(found) << name(cell) << " degree " << d;
      }
    }
  }
}

TEST(RuleLibrary, QueryPrefersPositiveInteriorAndFewestPoints) {
  // Hammer's 4-point degree-3 triangle rule has a negative weight: never chosen.
  const QuadratureRule& r3 = quadrature_rule(CellType::Triangle, 3);
  EXPECT_TRUE(r3.positive_interior());
  EXPECT_NE(r3.id, "hammer-4");
  // Witherden–Vincent's degree-16 triangle rule has points on the edges: the
  // query returns Papanicolopulos' 52-point rotationally symmetric rule instead.
  const QuadratureRule& r16 = quadrature_rule(CellType::Triangle, 16);
  EXPECT_EQ(r16.id, "Pap16-16-52");
  // Equal point counts at tet degree 9: WV15's points sit 6e-10 from the vertices,
  // CCGV22's 1e-3 inside; the query takes the one with the larger margin.
  EXPECT_EQ(quadrature_rule(CellType::Tetrahedron, 9).id, "CCGV22-9-59");
  // Symmetric rules beat collapsed ones with the same point count.
  EXPECT_EQ(quadrature_rule(CellType::Tetrahedron, 3).family, RuleFamily::Published);
}

TEST(RuleLibrary, FallsBackToCollapsedGaussBeyondTheTables) {
  const QuadratureRule& r = quadrature_rule(CellType::Tetrahedron, 25);
  EXPECT_EQ(r.family, RuleFamily::GaussCollapsed);
  EXPECT_GE(r.degree, 25);
  const QuadratureRule& h = quadrature_rule(CellType::Hexahedron, 7);
  EXPECT_EQ(h.family, RuleFamily::GaussTensor);
  EXPECT_EQ(h.size(), 64);
}

TEST(RuleLibrary, CachedReferencesAreStableAndThreadSafe) {
  const QuadratureRule* first = &quadrature_rule(CellType::Triangle, 27);
  std::vector<std::thread> threads;
  std::vector<const QuadratureRule*> seen(8);
  for (int t = 0; t < 8; ++t)
    threads.emplace_back([&, t] { seen[t] = &quadrature_rule(CellType::Triangle, 27 + (t % 2)); });
  for (auto& th : threads) th.join();
  for (int t = 0; t < 8; t += 2) EXPECT_EQ(seen[t], first);
  EXPECT_THROW(quadrature_rule(CellType::Triangle, -1), std::invalid_argument);
}

constexpr const char* kGood = R"(# Source: test
reference: 'T'
region: simplex
dim: 2
degree: 1
orbits: [1, 0, 0, 0, 0, 0, 0, 0]
positions:
weights:
  - '1.0'
)";

TEST(PublishedRules, ParsesAMinimalRule) {
  const QuadratureRule r = parse_published_rule(kGood, "good.yml");
  EXPECT_EQ(r.size(), 1);
  EXPECT_DOUBLE_EQ(r.weights[0], 0.5);
  EXPECT_DOUBLE_EQ(r.points(0, 0), 1.0 / 3.0);
}

void expect_error(const std::string& text, const std::string& fragment) {
  try {
    parse_published_rule(text, "bad.yml");
    ADD_FAILURE() << "no error for: " << fragment;
  } catch (const RuleFormatError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("bad.yml"), std::string::npos) << what;
    EXPECT_NE(what.find(fragment), std::string::npos) << what;
  }
}

TEST(PublishedRules, MalformedDataNamesFileLineAndProblem) {
  std::string s = kGood;
  expect_error(std::string(s).replace(s.find("degree: 1"), 9, "degree: x"), "bad.yml:5: 'x' is not a non-negative integer");
  expect_error(std::string(s).replace(s.find("'1.0'"), 5, "'1.0abc'"), "bad.yml:9: '1.0abc' is not a finite number");
  expect_error(std::string(s).replace(s.find("'1.0'"), 5, "'nan'"), "is not a finite number");
  expect_error(std::string(s) + "colour: blue\n", "bad.yml:10: unknown key 'colour'");
  expect_error(std::string(s).replace(s.find("[1, 0,"), 6, "[2, 0,"), "1 weights given for 2 orbits");
  expect_error(std::string(s).replace(s.find("[1, 0, 0, 0, 0, 0, 0, 0]"), 24, "[1, 0, 0]"), "orbits has 3 entries");
  expect_error(std::string(s).replace(s.find("[1, 0, 0, 0, 0, 0, 0, 0]"), 24, "[0, 1, 0, 0, 0, 0, 0, 0]"),
               "orbits need more positions");
  expect_error(std::string(s).replace(s.find("dim: 2\n"), 7, ""), "missing key 'dim'");
  expect_error(std::string(s).replace(s.find("dim: 2"), 6, "dim: 4"), "dim must be 2 or 3");
  expect_error("  - '1'\n", "bad.yml:1: list item outside");
  expect_error("just words\n", "bad.yml:1: expected 'key: value'");
}

TEST(PublishedRules, EveryEmbeddedFileParsesWithDistinctIds) {
  std::set<std::string> ids;
  for (CellType cell : {CellType::Triangle, CellType::Tetrahedron})
    for (const QuadratureRule& r : published_rules(cell)) {
      EXPECT_TRUE(ids.insert(std::string(name(cell)) + "/" + r.id).second) << r.id;
      EXPECT_FALSE(r.source.empty());
      EXPECT_FALSE(r.claimed_quality.empty()) << r.id;
    }
  EXPECT_EQ(ids.size(), 30u + 21u);
}

}  // namespace
}  // namespace hofem
