// The scene error's surface distance (Longva et al. 2020, §6.2: RMS and maximum of
// the distance from area-weighted samples on one surface to the other): the exact
// point-triangle distance region by region, the grid query against brute force
// (inside, on and far outside the grid, degenerate triangles included), and the
// directed and symmetric distances on surfaces whose distance is known in closed
// form (parallel squares) or bounded (a sphere against a scaled copy).
#include "study/surface_distance.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>

namespace hofem {
namespace {

// An n x n grid of squares split into 2 triangles each, [0,1]^2 at height z,
// then rotated by R and shifted by t.
TriangleSurface square(int n, double z, const Eigen::Matrix3d& R = Eigen::Matrix3d::Identity(),
                       const Eigen::Vector3d& t = Eigen::Vector3d::Zero()) {
  TriangleSurface s;
  s.points.resize(3, (n + 1) * (n + 1));
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      s.points.col(j * (n + 1) + i) = R * Eigen::Vector3d(double(i) / n, double(j) / n, z) + t;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
      s.triangles.push_back({a, b, c});
      s.triangles.push_back({a, c, d});
    }
  return s;
}

// The icosahedron subdivided `levels` times, vertices projected onto the unit sphere.
TriangleSurface icosphere(int levels) {
  const double g = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Eigen::Vector3d> v = {{-1, g, 0},  {1, g, 0},  {-1, -g, 0}, {1, -g, 0}, {0, -1, g},  {0, 1, g},
                                    {0, -1, -g}, {0, 1, -g}, {g, 0, -1},  {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
  std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                       {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                       {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                       {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (auto& x : v) x.normalize();
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int, int>, int> midpoint;
    const auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      if (auto it = midpoint.find(key); it != midpoint.end()) return it->second;
      v.push_back((v[a] + v[b]).normalized());
      return midpoint[key] = int(v.size()) - 1;
    };
    std::vector<std::array<int, 3>> finer;
    for (const auto& [a, b, c] : f) {
      const int ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      finer.insert(finer.end(), {{a, ab, ca}, {b, bc, ab}, {c, ca, bc}, {ab, bc, ca}});
    }
    f = std::move(finer);
  }
  TriangleSurface s;
  s.points.resize(3, Eigen::Index(v.size()));
  for (std::size_t i = 0; i < v.size(); ++i) s.points.col(Eigen::Index(i)) = v[i];
  s.triangles = f;
  return s;
}

// A torus (radii 1 and 0.3) of nu x nv quads split in two, every vertex moved by up
// to 0.3 of the grid step in each coordinate, stored as a soup (each triangle its
// own three points): irregular, non-convex, with repeated points.
TriangleSurface perturbed_torus_soup(int nu, int nv, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  const double step = 2.0 * M_PI * 0.3 / nv;
  Eigen::Matrix3Xd grid(3, nu * nv);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = 2.0 * M_PI * i / nu, w = 2.0 * M_PI * j / nv;
      grid.col(i * nv + j) = Eigen::Vector3d((1.0 + 0.3 * std::cos(w)) * std::cos(u),
                                             (1.0 + 0.3 * std::cos(w)) * std::sin(u), 0.3 * std::sin(w)) +
                             step * Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng));
    }
  TriangleSurface s;
  s.points.resize(3, 6 * nu * nv);
  int next = 0;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const int a = i * nv + j, b = ((i + 1) % nu) * nv + j, c = ((i + 1) % nu) * nv + (j + 1) % nv,
                d = i * nv + (j + 1) % nv;
      for (const auto& tri : {std::array<int, 3>{a, b, c}, std::array<int, 3>{a, c, d}}) {
        for (int k = 0; k < 3; ++k) s.points.col(next + k) = grid.col(tri[k]);
        s.triangles.push_back({next, next + 1, next + 2});
        next += 3;
      }
    }
  return s;
}

double brute_force_distance(const TriangleSurface& s, const Eigen::Vector3d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& [i, j, k] : s.triangles)
    best = std::min(best, (p - closest_point_on_triangle(p, s.points.col(i), s.points.col(j), s.points.col(k))).norm());
  return best;
}

// Query points: uniform in the surface's bounding box enlarged by 10 %, exactly on
// the surface (vertices and random points of triangles) and far outside (10, 1e3
// and 1e6 box sizes away in random directions).
std::vector<Eigen::Vector3d> probe_points(const TriangleSurface& s, int per_kind, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::Vector3d lo = s.points.rowwise().minCoeff(), hi = s.points.rowwise().maxCoeff();
  const Eigen::Vector3d centre = 0.5 * (lo + hi), extent = 1.1 * (hi - lo);
  const double size = (hi - lo).norm();
  std::vector<Eigen::Vector3d> out;
  for (int n = 0; n < per_kind; ++n) {
    const Eigen::Vector3d r(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5);
    out.push_back(centre + extent.cwiseProduct(r));
    const auto& [i, j, k] = s.triangles[std::size_t(unit(rng) * double(s.triangles.size())) % s.triangles.size()];
    double u = unit(rng), v = unit(rng);
    if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
    out.push_back(n % 4 == 0
                      ? Eigen::Vector3d(s.points.col(i))
                      : Eigen::Vector3d((1 - u - v) * s.points.col(i) + u * s.points.col(j) + v * s.points.col(k)));
    const Eigen::Vector3d direction = Eigen::Vector3d(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5).normalized();
    out.push_back(centre + std::pow(10.0, 1 + 2 * (n % 3) + (n % 3 == 2)) * size * direction);
  }
  return out;
}

// Grid query and brute force compute the same point-triangle distances, so they
// agree to rounding in the minimum only: 1e-14 relative to the distance (and to the
// surface's size for points on it, whose distance is ~1e-16).
void expect_matches_brute_force(const TriangleSurface& s, int per_kind, unsigned seed) {
  const TriangleDistanceQuery query(s);
  const double size = (s.points.rowwise().maxCoeff() - s.points.rowwise().minCoeff()).norm();
  for (const Eigen::Vector3d& p : probe_points(s, per_kind, seed)) {
    const double grid = query.distance(p), brute = brute_force_distance(s, p);
    ASSERT_TRUE(std::isfinite(grid)) << p.transpose();
    EXPECT_NEAR(grid, brute, 1e-14 * std::max(brute, size)) << "at " << p.transpose();
  }
}

TEST(SurfaceDistance, ClosestPointInEachVoronoiRegion) {
  // Triangle a = 0, b = e_x, c = e_y; each probe's closest point worked out by hand.
  const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  struct Case {
    const char* region;
    Eigen::Vector3d p, q;
  };
  const Case cases[] = {{"vertex a", {-1, -1, 2}, a},
                        {"vertex b", {2, -1, 0.5}, b},
                        {"vertex c", {-0.5, 3, -1}, c},
                        {"edge ab", {0.25, -2, 1}, {0.25, 0, 0}},
                        {"edge ac", {-3, 0.5, 0}, {0, 0.5, 0}},
                        {"edge bc", {1, 1, 1}, {0.5, 0.5, 0}},
                        {"face", {0.2, 0.3, -0.7}, {0.2, 0.3, 0}}};
  // Then the same in a rotated and shifted frame: the regions are decided by dot
  // products, so only rounding of coordinates of size ~5 changes (1e-14 is 20 ulp).
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Vector3d shift(-2, 0.5, 3);
  for (const Case& k : cases) {
    SCOPED_TRACE(k.region);
    EXPECT_LE((closest_point_on_triangle(k.p, a, b, c) - k.q).norm(), 1e-15);
    const Eigen::Vector3d q = closest_point_on_triangle(R * k.p + shift, R * a + shift, R * b + shift, R * c + shift);
    EXPECT_LE((q - (R * k.q + shift)).norm(), 1e-14);
    TriangleSurface one;
    one.points.resize(3, 3);
    one.points << R * a + shift, R * b + shift, R * c + shift;
    one.triangles = {{0, 1, 2}};
    EXPECT_NEAR(TriangleDistanceQuery(one).distance(R * k.p + shift), (k.p - k.q).norm(), 1e-14);
  }
}

TEST(SurfaceDistance, SameSurfaceIsAtZeroDistance) {
  // A sample (2/3, 1/6, 1/6) and its closest point rebuilt from the face-region
  // barycentrics differ by rounding of unit coordinates: measured <= 3.3e-16, and
  // 1e-15 of the bounding box's diagonal (3.5 for the sphere) is ten times that.
  for (const TriangleSurface& s : {icosphere(3), perturbed_torus_soup(24, 12, 7)}) {
    const double size = (s.points.rowwise().maxCoeff() - s.points.rowwise().minCoeff()).norm();
    const SurfaceDistance d = surface_distance(s, s);
    EXPECT_LE(d.rms(), 1e-15 * size);
    EXPECT_LE(d.max(), 1e-15 * size);
    EXPECT_EQ(d.a_to_b.samples, 3 * (long long)s.triangles.size());
    EXPECT_NEAR(d.a_to_b.area, s.area(), 1e-13 * s.area());
  }
}

TEST(SurfaceDistance, ParallelSquaresAreAtTheirOffset) {
  // Identical unit squares 0.3 apart: every sample and vertex projects into the other
  // square, so each distance is 0.3 up to the rounding of the coordinates (~1e-16);
  // 1e-14 leaves room for the RMS's sums over 128 triangles. The first frame has a
  // flat grid axis (one cell thick, no cell size), the second a generic orientation.
  const double offset = 0.3;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(1.1, Eigen::Vector3d(-1, 0.5, 2).normalized()).toRotationMatrix();
  for (const Eigen::Matrix3d& frame : {Eigen::Matrix3d(Eigen::Matrix3d::Identity()), R})
    for (int n : {1, 8}) {
      SCOPED_TRACE(::testing::Message() << "n = " << n);
      const Eigen::Vector3d shift(0.25, -4.0, 1.5);
      const TriangleSurface lower = square(n, 0.0, frame, shift), upper = square(n, offset, frame, shift);
      const SurfaceDistance d = surface_distance(lower, upper);
      for (const DirectedDistance& dd : {d.a_to_b, d.b_to_a}) {
        EXPECT_NEAR(dd.rms, offset, 1e-14);
        EXPECT_NEAR(dd.max, offset, 1e-14);
        EXPECT_NEAR(dd.area, 1.0, 1e-14);
        EXPECT_EQ(dd.samples, 3 * 2 * n * n);
      }
      EXPECT_NEAR(d.rms(), offset, 1e-14);
      EXPECT_NEAR(d.max(), offset, 1e-14);
    }
}

TEST(SurfaceDistance, SymmetricMeasureSeesTheLargerSurfacesExcess) {
  // The unit square against [0, 2]^2 in the same plane: every point of the small
  // square lies on the large one (a to b: 0), while the large square's points lie
  // up to sqrt(2) from the small one. b to a in closed form: dist^2 is (x - 1)^2,
  // (y - 1)^2 or their sum on the three uncovered unit squares (grid lines at
  // x, y = 1), integrating to 1/3 + 1/3 + 2/3 over area 4, so RMS = 1/sqrt(3);
  // the samples are exact for these quadratics on each triangle up to rounding
  // (~1e-16; 1e-13 leaves room for the sums over 256 triangles). A one-sided
  // measure would report 0 for (small, large) and 1/sqrt(3) only the other way round.
  const TriangleSurface small = square(4, 0.0), large = square(8, 0.0, 2.0 * Eigen::Matrix3d::Identity());
  for (const bool swapped : {false, true}) {
    SCOPED_TRACE(::testing::Message() << "swapped = " << swapped);
    const SurfaceDistance d = swapped ? surface_distance(large, small) : surface_distance(small, large);
    const DirectedDistance& on = swapped ? d.b_to_a : d.a_to_b;  // small -> large
    const DirectedDistance& off = swapped ? d.a_to_b : d.b_to_a;  // large -> small
    EXPECT_LE(on.rms, 1e-13);
    EXPECT_LE(on.max, 1e-13);
    EXPECT_NEAR(off.rms, 1.0 / std::sqrt(3.0), 1e-13);
    EXPECT_NEAR(off.max, std::sqrt(2.0), 1e-13);
    EXPECT_NEAR(d.rms(), 1.0 / std::sqrt(3.0), 1e-13);
    EXPECT_NEAR(d.max(), std::sqrt(2.0), 1e-13);
  }
}

TEST(SurfaceDistance, ScaledSphereIsWithinTheChordBound) {
  // Both surfaces are inscribed polyhedra: A's points lie at radii [1 - s, 1] and
  // B's at [(1 + d)(1 - s), 1 + d], s the largest sagitta 1 - sqrt(1 - rho^2) over
  // the triangles' circumradii rho (~h^2/6 for edge h; an edge's own is ~h^2/8).
  // A point of either surface is then between d - s (1 + d) and d + s from the
  // other (the ray from the centre through it meets the other surface in the other
  // shell, and nothing of the other surface is nearer than its inner radius).
  const double d = 0.01;
  const TriangleSurface a = icosphere(5);
  TriangleSurface b = a;
  b.points *= 1.0 + d;
  double rho = 0.0;
  for (const auto& [i, j, k] : a.triangles) {
    const Eigen::Vector3d u = a.points.col(j) - a.points.col(i), v = a.points.col(k) - a.points.col(i);
    rho = std::max(rho, u.norm() * v.norm() * (u - v).norm() / (2.0 * u.cross(v).norm()));
  }
  const double s = 1.0 - std::sqrt(1.0 - rho * rho);
  ASSERT_LT(s, d / 20) << "the tessellation is too coarse for the bound to say anything";
  const double low = d - s * (1.0 + d) - 1e-12, high = d + s + 1e-12;  // 1e-12: rounding of unit coordinates
  const SurfaceDistance result = surface_distance(a, b);
  for (const DirectedDistance& dd : {result.a_to_b, result.b_to_a}) {
    EXPECT_GE(dd.rms, low);
    EXPECT_LE(dd.rms, high);
    EXPECT_GE(dd.max, low);
    EXPECT_LE(dd.max, high);
  }
  EXPECT_EQ(result.a_to_b.samples, 3 * 20 * 1024);
  // The sampled areas are the two polyhedra's: 4 pi, less the chords' deficit.
  EXPECT_NEAR(result.b_to_a.area / result.a_to_b.area, (1 + d) * (1 + d), 1e-12);
  EXPECT_NEAR(result.a_to_b.area, 4 * M_PI, 4 * M_PI * 2 * s);
}

TEST(SurfaceDistance, GridQueryEqualsBruteForce) {
  // 1200 points against a jittered torus soup (1600 triangles) and against a flat
  // jittered square (a grid one cell thick).
  expect_matches_brute_force(perturbed_torus_soup(40, 20, 1), 400, 2);
  TriangleSurface flat = square(20, 0.0);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(-0.01, 0.01);
  for (Eigen::Index i = 0; i < flat.points.cols(); ++i)
    flat.points(0, i) += jitter(rng), flat.points(1, i) += jitter(rng);
  expect_matches_brute_force(flat, 400, 4);
}

TEST(SurfaceDistance, DegenerateTrianglesAreTolerated) {
  // Degenerate triangles are their edges: checked by hand first.
  const Eigen::Vector3d o(0, 0, 0), x2(2, 0, 0), x1(1, 0, 0), z2(0, 0, 2);
  EXPECT_NEAR((closest_point_on_triangle({1, 1, 0}, o, x2, x1) - x1).norm(), 0.0, 1e-15);  // collinear
  EXPECT_NEAR((closest_point_on_triangle({3, 0, 1}, o, x2, x1) - x2).norm(), 0.0, 1e-15);  // beyond its end
  EXPECT_NEAR((closest_point_on_triangle({1, 0, 1}, o, o, z2) - Eigen::Vector3d(0, 0, 1)).norm(), 0.0,
              1e-15);                                                                       // a repeated vertex
  EXPECT_NEAR((closest_point_on_triangle({1, 2, 2}, x1, x1, x1) - x1).norm(), 0.0, 1e-15);  // a point
  // A sliver (height 1e-10 over a unit base) just above the degeneracy threshold:
  // p is 1 above the base's midpoint, so 1 from the sliver to its height's order.
  EXPECT_NEAR(
      (Eigen::Vector3d(0.5, 0, 1) - closest_point_on_triangle({0.5, 0, 1}, o, {1, 0, 0}, {0.5, 1e-10, 0})).norm(), 1.0,
      1e-9);

  // A unit square at z = 0 with degenerate triangles in its plane and one segment
  // hanging 0.2 below it, then the square 0.3 above.
  TriangleSurface soup = square(4, 0.0);
  const Eigen::Index base = soup.points.cols();
  soup.points.conservativeResize(3, base + 5);
  soup.points.rightCols(5) << 0.2, 0.6, 0.4, 0.5, 0.5,  //
      0.3, 0.3, 0.3, 0.5, 0.5,                          //
      0.0, 0.0, 0.0, 0.0, -0.2;
  const int p = int(base);
  soup.triangles.insert(soup.triangles.end(),
                        {{p, p + 1, p + 2}, {p, p, p + 1}, {p + 3, p + 3, p + 3}, {p + 3, p + 4, p + 3}});
  expect_matches_brute_force(soup, 300, 5);
  const TriangleSurface upper = square(4, 0.3);
  // Zero-weight triangles leave the RMS, the samples and the area as the square's,
  // but their vertices count for the max: the hanging one is 0.5 from the upper
  // square. Downwards nothing of the degenerate triangles is nearer than the plane.
  const DirectedDistance up = directed_distance(soup, TriangleDistanceQuery(upper));
  EXPECT_NEAR(up.rms, 0.3, 1e-14);
  EXPECT_NEAR(up.max, 0.5, 1e-14);
  EXPECT_EQ(up.samples, 3 * 32);
  EXPECT_NEAR(up.area, 1.0, 1e-14);
  const DirectedDistance down = directed_distance(upper, TriangleDistanceQuery(soup));
  EXPECT_NEAR(down.rms, 0.3, 1e-14);
  EXPECT_NEAR(down.max, 0.3, 1e-14);
}

TEST(SurfaceDistance, InvalidSurfacesAreRefused) {
  const TriangleSurface good = square(2, 0.0);
  const TriangleDistanceQuery to_good(good);
  const auto expect_refused = [&](const TriangleSurface& bad, const char* what) {
    SCOPED_TRACE(what);
    EXPECT_THROW(TriangleDistanceQuery{bad}, std::invalid_argument);
    EXPECT_THROW(directed_distance(bad, to_good), std::invalid_argument);
    EXPECT_THROW(surface_distance(good, bad), std::invalid_argument);
    EXPECT_THROW(surface_distance(bad, good), std::invalid_argument);
  };
  expect_refused(TriangleSurface{}, "no triangles");
  TriangleSurface flat = good;
  flat.points.row(1).setZero();  // every triangle collinear: zero area
  expect_refused(flat, "zero area");
  for (int index : {-1, int(good.points.cols())}) {
    TriangleSurface bad = good;
    bad.triangles[3][1] = index;
    expect_refused(bad, "index out of range");
    try {
      TriangleDistanceQuery{bad};
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("vertex index " + std::to_string(index)), std::string::npos) << e.what();
    }
  }
  for (double value : {std::nan(""), std::numeric_limits<double>::infinity()}) {
    TriangleSurface bad = good;
    bad.points(2, 4) = value;
    expect_refused(bad, "non-finite point");
  }
  EXPECT_THROW(to_good.distance(Eigen::Vector3d(0, std::nan(""), 0)), std::invalid_argument);
}

TEST(SurfaceDistance, RmsDoesNotDependOnTheRun) {
  // Partial sums are per fixed chunk of triangles and added in chunk order, so
  // repeated runs (any thread count, any schedule) give the same bits.
  const TriangleSurface a = perturbed_torus_soup(60, 30, 11), b = perturbed_torus_soup(60, 30, 12);
  const TriangleDistanceQuery to_b(b);
  const DirectedDistance first = directed_distance(a, to_b);
  for (int run = 0; run < 3; ++run) {
    const DirectedDistance again = directed_distance(a, to_b);
    EXPECT_EQ(again.rms, first.rms);
    EXPECT_EQ(again.max, first.max);
    EXPECT_EQ(again.area, first.area);
  }
  EXPECT_GT(first.rms, 0.0);
}

}  // namespace
}  // namespace hofem
