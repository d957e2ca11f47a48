// Lagrange bases: behaviour the table-driven suite does not cover (closed forms of
// the thesis, tabulation layout and caching, argument errors).
#include "basis/basis_tabulation.hpp"
#include "basis/lagrange_nodes.hpp"
#include "basis/reference_basis.hpp"
#include "quadrature/rule_library.hpp"

#include <gtest/gtest.h>

namespace hofem {
namespace {

// Thesis appendix Table 2 (Tet10) in volume coordinates L1 = xi, L2 = eta,
// L3 = mu, L4 = 1 - xi - eta - mu: vertex functions L(2L - 1), edge functions 4 La Lb.
// Our Gmsh-ordered Tet10 must equal these closed forms node by node.
TEST(SimplexLagrangeBasis, Tet10MatchesThesisClosedForms) {
  const ReferenceBasis& b = lagrange_basis(CellType::Tetrahedron, 2);
  for (const Eigen::Vector3d& x : {Eigen::Vector3d(0.1, 0.2, 0.3), Eigen::Vector3d(0.25, 0.05, 0.6)}) {
    const double L[4] = {1 - x.sum(), x[0], x[1], x[2]};  // Gmsh vertex k <-> barycentric L[k]
    const Eigen::VectorXd N = b.evaluate(x);
    for (int v = 0; v < 4; ++v) EXPECT_NEAR(N[v], L[v] * (2 * L[v] - 1), 1e-14);
    const int edges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}};
    for (int e = 0; e < 6; ++e) EXPECT_NEAR(N[4 + e], 4 * L[edges[e][0]] * L[edges[e][1]], 1e-14);
  }
}

// Thesis Table 1, cubic triangle: the interior (bubble) function is 27 L1 L2 L3.
TEST(SimplexLagrangeBasis, Tri10BubbleMatchesThesis) {
  const ReferenceBasis& b = lagrange_basis(CellType::Triangle, 3);
  const Eigen::Vector2d x(0.2, 0.3);
  EXPECT_NEAR(b.evaluate(x)[9], 27 * x[0] * x[1] * (1 - x.sum()), 1e-14);
}

TEST(SimplexLagrangeBasis, NamesAndSizes) {
  EXPECT_EQ(lagrange_basis(CellType::Tetrahedron, 1).element_name(), "Tet4");
  EXPECT_EQ(lagrange_basis(CellType::Tetrahedron, 3).element_name(), "Tet20");
  EXPECT_EQ(lagrange_basis(CellType::Tetrahedron, 6).size(), 84);
  EXPECT_EQ(lagrange_basis(CellType::Triangle, 6).size(), 28);
  EXPECT_EQ(lagrange_basis(CellType::Segment, 4).element_name(), "Line5");
  EXPECT_EQ(lagrange_basis(CellType::Hexahedron, 2).element_name(), "Hex20");
}

TEST(SimplexLagrangeBasis, HighOrderNodesAreDistinctAndOnTheLattice) {
  for (int p = 1; p <= 8; ++p) {
    const auto l = tetrahedron_lattice(p);
    ASSERT_EQ(static_cast<int>(l.size()), (p + 1) * (p + 2) * (p + 3) / 6);
    std::set<std::array<int, 3>> unique(l.begin(), l.end());
    EXPECT_EQ(unique.size(), l.size()) << "order " << p;
    for (const auto& n : l) EXPECT_LE(n[0] + n[1] + n[2], p);
  }
}

TEST(ReferenceBasis, RejectsUnsupportedRequests) {
  EXPECT_THROW(make_lagrange_basis(CellType::Tetrahedron, 0), std::invalid_argument);
  EXPECT_THROW(make_lagrange_basis(CellType::Hexahedron, 3), std::invalid_argument);
  EXPECT_THROW(make_lagrange_basis(CellType::Quadrilateral, 1), std::invalid_argument);
}

TEST(BasisTabulation, LayoutMatchesPointwiseEvaluationAndIsCached) {
  const BasisTabulation& t = cached_tabulation(CellType::Tetrahedron, 3, 4);
  const QuadratureRule& rule = quadrature_rule(CellType::Tetrahedron, 4);
  const ReferenceBasis& b = lagrange_basis(CellType::Tetrahedron, 3);
  ASSERT_EQ(t.num_points, rule.size());
  ASSERT_EQ(t.num_basis, 20);
  for (int q = 0; q < t.num_points; ++q) {
    EXPECT_EQ((t.values.col(q) - b.evaluate(rule.points.col(q))).norm(), 0.0);
    EXPECT_EQ((t.gradient(q) - b.gradients(rule.points.col(q))).norm(), 0.0);
  }
  EXPECT_EQ(&cached_tabulation(CellType::Tetrahedron, 3, 4), &t);
  // Integrating N_i over the cell with the tabulation: sum_i int N_i = |cell|.
  EXPECT_NEAR((t.values * rule.weights).sum(), 1.0 / 6.0, 1e-15);
  EXPECT_THROW(tabulate(b, quadrature_rule(CellType::Triangle, 2)), std::invalid_argument);
}

}  // namespace
}  // namespace hofem
