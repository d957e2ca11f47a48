// Surface rules on an embedded boundary clipped by the background cells
// (embedded/embedded_surface_quadrature.hpp): the load of a traction on a
// surface that crosses cell faces, where the background functions have kinks.
#include "embedded/embedded_surface_quadrature.hpp"

#include "mesh/box_mesh.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace hofem {
namespace {

/// One linear triangle as a surface mesh.
Mesh triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  Mesh m;
  m.cell = CellType::Triangle;
  m.order = 1;
  m.nodes.resize(3, 3);
  m.nodes << a, b, c;
  m.elements.resize(3, 1);
  m.elements << 0, 1, 2;
  return m;
}

/// Nodal values of the field v(X) = max(0, x - 1/2) e_x: linear in each cell of a
/// grid with a plane at x = 1/2 (so Hex8 and Hex20 represent it exactly), with a
/// kink across that plane.
Eigen::VectorXd kinked_field(const Mesh& background) {
  Eigen::VectorXd v = Eigen::VectorXd::Zero(3 * background.num_nodes());
  for (int n = 0; n < background.num_nodes(); ++n) v[3 * n] = std::max(0.0, background.nodes(0, n) - 0.5);
  return v;
}

// The cause of the stalled Fig. 10 Hex20 curve: a triangle crossing the cell face
// x = 1/2 with the field above. Its work under t = e_x is, by hand,
//   ∫_T max(0, x - 1/2) dA, T = {x, y >= 0.1, x + y <= 1} at z = 0.3
//   = ∫_0.5^0.9 (x - 0.5)(0.9 - x) dx = 0.4^3 / 6 = 4 / 375.
// The clipped rule integrates a polynomial on each side of the face: exact to
// rounding (1e-14 relative: tens of terms, each exact to ~1e-16). One rule of the
// same degree over the whole triangle misses it by 0.3 % (Hex20: 0.010699) and
// 16 % (Hex8: 0.008919).
TEST(EmbeddedSurfaceQuadrature, TractionWorkAcrossACellFaceIsExact) {
  const Mesh surface = triangle({0.1, 0.1, 0.3}, {0.9, 0.1, 0.3}, {0.1, 0.9, 0.3});
  for (int order : {1, 2}) {
    const Mesh background = box_mesh(unit_cube(4), CellType::Hexahedron, order);
    const EmbeddedSurfaceRule rule = embedded_surface_rule(background, surface, 2 * order + 2);
    EXPECT_NEAR(rule.weights.sum(), 0.32, 1e-15);  // the triangle's area, once
    const Eigen::VectorXd b = surface_load_vector(
        background, rule, [](const Eigen::Vector3d&, const Eigen::Vector3d&) { return Eigen::Vector3d::UnitX(); });
    const double exact = 4.0 / 375.0;
    EXPECT_NEAR(b.dot(kinked_field(background)), exact, 1e-14 * exact) << "order " << order;
  }
}

// A triangle lying in a cell face (the plane z = 1/2 of a 4^3 grid) is counted
// once, by the cell on the body's side: below the face for an upward (outward)
// normal, above it for a downward one.
TEST(EmbeddedSurfaceQuadrature, TriangleInACellFaceGoesToTheCellBehindIt) {
  const Mesh background = box_mesh(unit_cube(4), CellType::Hexahedron, 2);
  const Eigen::Vector3d a(0.1, 0.1, 0.5), b(0.8, 0.2, 0.5), c(0.3, 0.9, 0.5);
  const double area = 0.5 * (b - a).cross(c - a).norm();
  for (const bool upward : {true, false}) {
    const Mesh surface = upward ? triangle(a, b, c) : triangle(a, c, b);
    const EmbeddedSurfaceRule rule = embedded_surface_rule(background, surface, 4);
    ASSERT_GT(rule.size(), 0);
    EXPECT_NEAR(rule.weights.sum(), area, 1e-15 * 8);
    for (int q = 0; q < rule.size(); ++q) {
      EXPECT_NEAR(rule.normals(2, q), upward ? 1.0 : -1.0, 1e-15);
      // Reference z of the point in its cell: +1 is the cell's top face.
      EXPECT_NEAR(rule.xi(2, q), upward ? 1.0 : -1.0, 1e-12);
    }
  }
}

// The same where h is not a binary fraction (1/6, 1/10): the face planes' reference
// coordinates round to either side of +-1, and a triangle in a face must still be
// counted once - on the background's boundary (z = 0, body above) and inside it.
// Before the on-plane tolerance of the clip, the flat face of the Fig. 10 half ball
// on z = 0 of the h = 1/6 grid was lost.
TEST(EmbeddedSurfaceQuadrature, TriangleInAFaceIsCountedOnceWhateverTheRounding) {
  for (int n : {6, 10}) {
    const Mesh background = box_mesh(unit_cube(n), CellType::Hexahedron, 1);
    for (double z : {0.0, 2.0 / n, 0.5}) {  // grid planes
      const Eigen::Vector3d a(0.13, 0.07, z), b(0.71, 0.29, z), c(0.37, 0.93, z);
      const double area = 0.5 * (b - a).cross(c - a).norm();
      for (const bool upward : {false, true}) {
        if (z == 0.0 && upward) continue;  // the body would lie outside the background
        const Mesh surface = upward ? triangle(a, b, c) : triangle(a, c, b);
        const EmbeddedSurfaceRule rule = embedded_surface_rule(background, surface, 2);
        EXPECT_NEAR(rule.weights.sum(), area, 1e-14) << "n = " << n << ", z = " << z << (upward ? " up" : " down");
      }
    }
  }
}

// Points in inactive cells (dropped slivers) move to the nearest active cell and
// are evaluated by extrapolation: the basis still sums to one there, so the total
// force equals ∫ t dA (1e-14: rounding of a few hundred terms).
TEST(EmbeddedSurfaceQuadrature, InactiveCellsHandTheirPointsToActiveOnes) {
  const Mesh background = box_mesh(unit_cube(4), CellType::Hexahedron, 2);
  const Mesh surface = triangle({0.1, 0.1, 0.3}, {0.9, 0.1, 0.3}, {0.1, 0.9, 0.3});
  std::vector<char> active(background.num_elements(), 1);
  for (int e = 0; e < background.num_elements(); ++e) {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (int i = 0; i < 8; ++i) centre += background.nodes.col(background.elements(i, e)) / 8.0;
    if (centre.x() > 0.5) active[e] = 0;  // the cells of x > 1/2
  }
  const EmbeddedSurfaceRule rule = embedded_surface_rule(background, surface, 6, active);
  EXPECT_GT(rule.num_relocated, 0);
  for (int q = 0; q < rule.size(); ++q) EXPECT_TRUE(active[rule.element[q]]);
  const Eigen::Vector3d t(0.3, -1.2, 0.7);
  const Eigen::VectorXd b =
      surface_load_vector(background, rule, [&](const Eigen::Vector3d&, const Eigen::Vector3d&) { return t; });
  Eigen::Vector3d total = Eigen::Vector3d::Zero();
  for (int n = 0; n < background.num_nodes(); ++n) total += b.segment<3>(3 * n);
  EXPECT_LE((total - 0.32 * t).norm(), 1e-14 * t.norm());
}

TEST(EmbeddedSurfaceQuadrature, RejectsWhatItCannotIntegrate) {
  const Mesh background = box_mesh(unit_cube(2), CellType::Hexahedron, 1);
  EXPECT_THROW(embedded_surface_rule(background, box_mesh(unit_cube(1), CellType::Tetrahedron, 1), 2),
               std::invalid_argument);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(embedded_surface_rule(background, triangle({0, 0, 0}, {nan, 0, 0}, {0, 1, 0}), 2), std::invalid_argument);
  EXPECT_THROW(embedded_surface_rule(background, triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}), 2, std::vector<char>(3, 1)),
               std::invalid_argument);
}

}  // namespace
}  // namespace hofem
