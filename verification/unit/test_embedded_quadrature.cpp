// Embedded quadrature, Longva et al. 2020 §4.5: clipping tetrahedra by half-spaces,
// per-cell rules over (embedded geometry ∩ cell), and the bucket grid that finds
// each cell's candidate tetrahedra.
#include "embedded/embedded_quadrature.hpp"
#include "embedded/tet_clipping.hpp"
#include "mesh/box_mesh.hpp"
#include "quadrature/rule_library.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace hofem {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

Tetrahedron unit_tet() {
  Tetrahedron t;
  t.v << 0, 1, 0, 0,  //
      0, 0, 1, 0,     //
      0, 0, 0, 1;
  return t;
}

double volume(const std::vector<Tetrahedron>& pieces) {
  double v = 0.0;
  for (const auto& p : pieces) v += p.volume();
  return v;
}

// Each clipping case against a volume computed by hand on the unit tet (1/6):
// 3 vertices kept (x <= 1/2: 1/6 - (1/2)^3/6), 1 kept (x >= 1/2: (1/2)^3/6),
// 2 kept (x + y <= 1/2: int_0^1/2 1/8 dz + int_1/2^1 (1-z)^2/2 dz = 1/12), all and
// none. The pieces are sums of a few tets: 8 eps relative.
TEST(TetClipping, VolumesOfEveryCase) {
  const Tetrahedron t = unit_tet();
  struct Case {
    HalfSpace h;
    double volume;
    size_t pieces;
  };
  const Case cases[] = {{{Eigen::Vector3d(1, 0, 0), 0.5}, (1.0 - 0.125) / 6.0, 3},
                        {{Eigen::Vector3d(-1, 0, 0), -0.5}, 0.125 / 6.0, 1},
                        {{Eigen::Vector3d(1, 1, 0), 0.5}, 1.0 / 12.0, 3},
                        {{Eigen::Vector3d(1, 1, 1), 2.0}, 1.0 / 6.0, 1},
                        {{Eigen::Vector3d(1, 1, 1), -0.1}, 0.0, 0}};
  for (const Case& c : cases) {
    std::vector<Tetrahedron> out;
    clip_tetrahedron(t, c.h, out, 0.0);
    EXPECT_EQ(out.size(), c.pieces);
    EXPECT_NEAR(volume(out), c.volume, 8 * kEps) << c.h.n.transpose() << " <= " << c.h.d;
    for (const auto& p : out)
      for (int i = 0; i < 4; ++i) EXPECT_LE(c.h.signed_distance(p.v.col(i)), 1e-15);
  }
  // A cell given by its own half-spaces keeps the tet whole; the box [0, 1/2]^3
  // keeps the corner tet of edge 1/2 ((1/2)^3/6) and more: x + y + z <= 1 inside
  // the box is the box minus the corner beyond the plane, 1/8 - (1/2)^3/6.
  EXPECT_NEAR(volume(clip_tetrahedron(t, tetrahedron_half_spaces(t))), 1.0 / 6.0, 8 * kEps);
  const auto box = box_half_spaces(Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(0.5));
  EXPECT_NEAR(volume(clip_tetrahedron(t, box)), 0.125 - 0.125 / 6.0, 16 * kEps);
}

// A rotated, translated cuboid (the Fig. 4 geometry of Longva et al. 2020) meshed by
// tetrahedra and cut by a 3x3x3 background grid: summed over the cells, the
// per-cell rules of degree m integrate every monomial of degree <= m over the
// whole cuboid, against a tensor Gauss rule mapped affinely onto the cuboid
// (exact for these degrees). Errors relative to the integral of |monomial|:
// each cell rule is exact, so only rounding (~1e-15 per point, 1e4 points) remains.
TEST(EmbeddedQuadrature, CellRulesOfACutCuboidSumToItsMoments) {
  const Eigen::Vector3d extent(0.7, 0.5, 0.3), centre(0.52, 0.47, 0.55);
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized())).toRotationMatrix();
  Mesh cuboid = box_mesh(BoxSpec{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}}, CellType::Tetrahedron, 1);
  for (int i = 0; i < cuboid.num_nodes(); ++i)
    cuboid.nodes.col(i) = centre + R * ((cuboid.nodes.col(i) - Eigen::Vector3d::Constant(0.5)).cwiseProduct(extent));
  const std::vector<Tetrahedron> tets = mesh_tetrahedra(cuboid);
  const BoxBucketGrid grid(bounding_boxes(tets));
  for (int m : {1, 2, 3, 5}) {
    PhysicalRule total;
    const double h = 1.0 / 3.0;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k) {
          const Eigen::Vector3d lo(i * h, j * h, k * h);
          const PhysicalRule r = box_cell_rule(tets, grid, lo, lo + Eigen::Vector3d::Constant(h), m);
          total.points.insert(total.points.end(), r.points.begin(), r.points.end());
          total.weights.insert(total.weights.end(), r.weights.begin(), r.weights.end());
          for (double w : r.weights) ASSERT_GT(w, 0.0);
          for (const auto& p : r.points)
            ASSERT_TRUE((p.array() >= lo.array() - 1e-12).all() && (p.array() <= lo.array() + h + 1e-12).all());
        }
    const QuadratureRule& g = quadrature_rule(CellType::Hexahedron, m);  // on [-1, 1]^3
    const double jac = extent.prod() / 8.0;
    for (int a = 0; a <= m; ++a)
      for (int b = 0; a + b <= m; ++b)
        for (int c = 0; a + b + c <= m; ++c) {
          auto f = [&](const Eigen::Vector3d& x) { return std::pow(x.x(), a) * std::pow(x.y(), b) * std::pow(x.z(), c); };
          double exact = 0.0, scale = 0.0, got = 0.0;
          for (int q = 0; q < g.size(); ++q) {
            const Eigen::Vector3d x = centre + R * (0.5 * g.points.col(q)).cwiseProduct(extent);
            exact += jac * g.weights[q] * f(x);
            scale += jac * g.weights[q] * std::abs(f(x));
          }
          for (int q = 0; q < total.size(); ++q) got += total.weights[q] * f(total.points[q]);
          EXPECT_LE(std::abs(got - exact), 1e-13 * scale) << "m = " << m << ", monomial " << a << b << c;
        }
  }
}

// The grid returns exactly the tets whose bounding boxes overlap the query box
// (checked against brute force on random boxes).
TEST(EmbeddedQuadrature, BucketGridFindsEveryOverlappingTet) {
  const Mesh m = box_mesh(BoxSpec{{0, 0, 0}, {2, 1, 1}, {6, 3, 3}}, CellType::Tetrahedron, 1);
  const std::vector<Tetrahedron> tets = mesh_tetrahedra(m);
  const BoxBucketGrid grid(bounding_boxes(tets));
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> u(-0.3, 2.3);
  for (int trial = 0; trial < 200; ++trial) {
    Eigen::Vector3d a(u(gen), u(gen) / 2, u(gen) / 2), b(u(gen), u(gen) / 2, u(gen) / 2);
    const Eigen::Vector3d lo = a.cwiseMin(b), hi = a.cwiseMax(b);
    std::vector<int> brute;
    for (size_t k = 0; k < tets.size(); ++k)
      if ((tets[k].v.rowwise().minCoeff().array() <= hi.array()).all() &&
          (tets[k].v.rowwise().maxCoeff().array() >= lo.array()).all())
        brute.push_back(static_cast<int>(k));
    EXPECT_EQ(grid.candidates(lo, hi), brute);
  }
}

}  // namespace
}  // namespace hofem
