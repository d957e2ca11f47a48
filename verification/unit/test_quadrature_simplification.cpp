// Quadrature simplification, Longva et al. 2020 §4.4: a subset of at most M points with
// positive weights that keeps every moment of degree <= m of the input rule.
#include "embedded/embedded_quadrature.hpp"
#include "embedded/quadrature_simplification.hpp"
#include "mesh/box_mesh.hpp"
#include "mesh/tube_mesh.hpp"
#include "quadrature/rule_library.hpp"

#include <Eigen/LU>
#include <Eigen/SVD>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <thread>

namespace hofem {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// Both ways to a basic feasible point are held to the same bounds: the active set
// (the default; each case checks that it really was the active set that answered,
// not its simplex fallback) and the simplex alone.
constexpr SimplificationMethod kMethods[] = {SimplificationMethod::ActiveSet, SimplificationMethod::Simplex};
SimplificationOptions with(SimplificationMethod method) {
  SimplificationOptions o;
  o.method = method;
  return o;
}
const char* expected_name(SimplificationMethod method) {
  return method == SimplificationMethod::ActiveSet ? "active set" : "simplex";
}

struct Rule {
  Eigen::MatrixXd points;
  Eigen::VectorXd weights;
};

// The degree-m tet rule mapped onto the 6 n^3 Kuhn tets of the box [lo, hi]:
// exact to degree m on the box, with many more points than M.
Rule tet_subdivided_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int n, int m) {
  const Mesh mesh = box_mesh(BoxSpec{{lo.x(), lo.y(), lo.z()}, {hi.x(), hi.y(), hi.z()}, {n, n, n}},
                             CellType::Tetrahedron, 1);
  const QuadratureRule& ref = quadrature_rule(CellType::Tetrahedron, m);
  const std::vector<Tetrahedron> tets = mesh_tetrahedra(mesh);
  Rule r;
  r.points.resize(3, static_cast<Eigen::Index>(tets.size()) * ref.size());
  r.weights.resize(r.points.cols());
  Eigen::Index q = 0;
  for (const Tetrahedron& t : tets) {
    Eigen::Matrix3d J;
    J << t.v.col(1) - t.v.col(0), t.v.col(2) - t.v.col(0), t.v.col(3) - t.v.col(0);
    for (int i = 0; i < ref.size(); ++i, ++q) {
      r.points.col(q) = t.v.col(0) + J * ref.points.col(i);
      r.weights[q] = std::abs(J.determinant()) * ref.weights[i];
    }
  }
  return r;
}

// Largest |Q_s(f) - Q_0(f)| / Q_0(|f|) over the monomials f = u^a v^b w^c,
// a + b + c <= m, of the local coordinates u = (x - origin) / size (per axis).
double max_monomial_difference(const Rule& original, const SimplifiedRule& s, int m, const Eigen::Vector3d& origin,
                               const Eigen::Vector3d& size) {
  auto integrate = [&](const Eigen::MatrixXd& x, const Eigen::VectorXd& w, int a, int b, int c, bool absolute) {
    long double sum = 0.0L;
    for (Eigen::Index j = 0; j < w.size(); ++j) {
      const Eigen::Vector3d u = (x.col(j) - origin).cwiseQuotient(size);
      const double f = std::pow(u.x(), a) * std::pow(u.y(), b) * std::pow(u.z(), c);
      sum += w[j] * (absolute ? std::abs(f) : f);
    }
    return sum;
  };
  double worst = 0.0;
  for (int a = 0; a <= m; ++a)
    for (int b = 0; a + b <= m; ++b)
      for (int c = 0; a + b + c <= m; ++c) {
        const long double q0 = integrate(original.points, original.weights, a, b, c, false);
        const long double q1 = integrate(s.points, s.weights, a, b, c, false);
        const long double scale = integrate(original.points, original.weights, a, b, c, true);
        if (!(scale > 0.0L)) return std::numeric_limits<double>::infinity();
        worst = std::max(worst, static_cast<double>(std::fabs(q1 - q0) / scale));
      }
  return worst;
}

// The bound on max_monomial_difference implied by the moment residual, for
// points whose local coordinates u lie in [0, 1]^3 and a rule over [0, 1]^3 (in u):
// per axis u = alpha + beta t with t the bounding-box coordinate, alpha >= beta
// >= 0 and alpha + beta <= 1, so the Chebyshev coefficients of u^a v^b w^c sum
// to at most 1 in magnitude and |Q_s(f) - Q_0(f)| <= residual x volume; and
// Q_0(f) = volume / ((a+1)(b+1)(c+1)) >= volume / 18 for a + b + c <= 5. Each
// term of the sums is evaluated to ~(m + 2) eps relative (positive terms), in
// both rules: 2 (m + 2) eps more.
double monomial_bound(const SimplifiedRule& s, int m) { return 18.0 * s.moment_residual + 2.0 * (m + 2) * kEps; }

// Every output point is an input point, bit for bit.
bool is_subset(const SimplifiedRule& s, const Rule& r) {
  for (Eigen::Index k = 0; k < s.points.cols(); ++k) {
    bool found = false;
    for (Eigen::Index j = 0; j < r.points.cols() && !found; ++j) found = (s.points.col(k).array() == r.points.col(j).array()).all();
    if (!found) return false;
  }
  return true;
}

// A box rule with 48 tets (N = 48 x tet rule size, 48 to 672 points) reduces to
// at most M points. The refined weights solve the kept columns' equations to
// rounding: the Chebyshev moment residual (relative to the volume) is a few eps
// times the conditioning of those columns, measured <= 3.1e-16 here; 2e-15 (9 eps)
// allows for another platform's rounding and catches anything that only meets
// GLPK's tolerances (~1e-9). Monomials are held to monomial_bound (above), which
// a basis that is not exactly polynomial in the points would break (a clamped
// map did: 1.4e-14 against a bound of 5e-15).
TEST(QuadratureSimplification, TetSubdividedBoxKeepsMomentsWithAtMostMPoints) {
  const Eigen::Vector3d lo(0.1, -0.3, 0.2), hi(0.9, 0.5, 0.7);
  for (const SimplificationMethod method : kMethods)
    for (int m : {1, 2, 3, 5}) {
      const Rule r = tet_subdivided_box(lo, hi, 2, m);
      const SimplifiedRule s = simplify_quadrature(r.points, r.weights, m, with(method));
      const int M = (m + 1) * (m + 2) * (m + 3) / 6;
      ASSERT_TRUE(s.simplified) << "m = " << m << ": " << s.message;
      EXPECT_EQ(s.method, expected_name(method)) << s.message;
      EXPECT_EQ(s.points_before, r.weights.size());
      EXPECT_EQ(s.basis_size, M);
      EXPECT_EQ(s.rank, M) << "points spread over a box: P has full rank";
      EXPECT_LE(s.size(), M);
      EXPECT_GT(s.size(), 0);
      EXPECT_TRUE(is_subset(s, r));
      EXPECT_GT(s.weights.minCoeff(), 0.0);
      EXPECT_LE(s.moment_residual, 2e-15) << "m = " << m;
      EXPECT_LE(max_monomial_difference(r, s, m, lo, hi - lo), monomial_bound(s, m)) << "m = " << m;
      // The volume is the degree-0 moment (T_0 = 1): kept to the residual.
      EXPECT_NEAR(s.weights.sum(), r.weights.sum(), 2e-15 * r.weights.sum());
    }
}

// A cluster of diameter ~1e-3 inside [-1, 1]^3 (a cell cut by a tiny piece of
// geometry). Chebyshev polynomials of [-1, 1]^3 barely vary over it: the singular
// values of their matrix fall by ~(1e-3)^k for degree k, so at m = 4 it is
// numerically rank-deficient at the rank tolerance (1e-13), and constraints
// dropped with those singular values would leave moments of the cluster's own
// scale unfitted. The bounding-box basis restores full rank, and the moments in the
// cluster's local coordinates are kept as for a unit box (same tolerances).
TEST(QuadratureSimplification, TinyClusterNeedsTheBoundingBoxBasis) {
  const int m = 4, M = 35;
  const Eigen::Vector3d lo(0.3, -0.6, 0.45);
  const double size = 6e-4;  // edge; diameter ~1e-3
  const Rule r = tet_subdivided_box(lo, lo + Eigen::Vector3d::Constant(size), 2, m);

  // The basis of [-1, 1]^3 without the bounding-box map, for comparison.
  Eigen::MatrixXd P(M, r.points.cols());
  for (Eigen::Index j = 0; j < P.cols(); ++j) {
    Eigen::Matrix<double, 3, m + 1> T;  // T_a(x_d) by the three-term recurrence
    T.col(0).setOnes();
    T.col(1) = r.points.col(j);
    for (int a = 2; a <= m; ++a) T.col(a) = 2.0 * r.points.col(j).cwiseProduct(T.col(a - 1)) - T.col(a - 2);
    int k = 0;
    for (int a = 0; a <= m; ++a)
      for (int b = 0; a + b <= m; ++b)
        for (int c = 0; a + b + c <= m; ++c) P(k++, j) = T(0, a) * T(1, b) * T(2, c);
  }
  const Eigen::VectorXd sv = Eigen::JacobiSVD<Eigen::MatrixXd>(P).singularValues();
  EXPECT_LT(sv[M - 1] / sv[0], 1e-13) << "unscaled basis: numerically rank-deficient";

  for (const SimplificationMethod method : kMethods) {
    const SimplifiedRule s = simplify_quadrature(r.points, r.weights, m, with(method));
    ASSERT_TRUE(s.simplified) << s.message;
    EXPECT_EQ(s.method, expected_name(method)) << s.message;
    EXPECT_EQ(s.rank, M) << "bounding-box basis: full rank";
    EXPECT_LE(s.size(), M);
    EXPECT_TRUE(is_subset(s, r));
    EXPECT_GT(s.weights.minCoeff(), 0.0);
    EXPECT_LE(s.moment_residual, 2e-15);
    EXPECT_LE(max_monomial_difference(r, s, m, lo, Eigen::Vector3d::Constant(size)), monomial_bound(s, m));
  }
}

// Points on the plane z = 0.25 (a flat cut): the z-axis has zero extent, only the
// C(m+2, 2) polynomials in x, y are independent, and at most that many points are
// kept. Same tolerances as the box (the local w = z + 0.75 is 1 on the plane).
TEST(QuadratureSimplification, FlatPointSetLowersTheRank) {
  const int m = 4;
  const QuadratureRule& tri = quadrature_rule(CellType::Triangle, m);
  Rule r;
  const int copies = 8;  // 8 triangles of a 2x2 grid of squares in [0, 1]^2
  r.points.resize(3, copies * tri.size());
  r.weights.resize(copies * tri.size());
  Eigen::Index q = 0;
  for (int cell = 0; cell < 4; ++cell) {
    const Eigen::Vector2d o(0.5 * (cell % 2), 0.5 * (cell / 2));
    for (int flip = 0; flip < 2; ++flip)
      for (int i = 0; i < tri.size(); ++i, ++q) {
        const Eigen::Vector2d xi = tri.points.col(i);
        const Eigen::Vector2d p = flip ? Eigen::Vector2d(o + 0.5 * Eigen::Vector2d(1 - xi.y(), 1 - xi.x()))
                                       : Eigen::Vector2d(o + 0.5 * xi);
        r.points.col(q) << p, 0.25;
        r.weights[q] = 0.25 * tri.weights[i];
      }
  }
  for (const SimplificationMethod method : kMethods) {
    const SimplifiedRule s = simplify_quadrature(r.points, r.weights, m, with(method));
    ASSERT_TRUE(s.simplified) << s.message;
    EXPECT_EQ(s.method, expected_name(method)) << s.message;
    EXPECT_EQ(s.rank, (m + 1) * (m + 2) / 2);
    EXPECT_LE(s.size(), s.rank);
    EXPECT_TRUE(is_subset(s, r));
    EXPECT_GT(s.weights.minCoeff(), 0.0);
    EXPECT_LE(s.moment_residual, 2e-15);
    EXPECT_LE(max_monomial_difference(r, s, m, Eigen::Vector3d(0, 0, -0.75), Eigen::Vector3d::Ones()),
              monomial_bound(s, m));
  }
}

// An active set cut short (one iteration cannot reach the moments) hands over to the
// simplex, whose answer meets the same bounds; the message says what happened.
TEST(QuadratureSimplification, ActiveSetFallsBackToTheSimplex) {
  const Eigen::Vector3d lo(0.1, -0.3, 0.2), hi(0.9, 0.5, 0.7);
  const int m = 3;
  const Rule r = tet_subdivided_box(lo, hi, 2, m);
  SimplificationOptions o;
  o.active_set_iterations = 1;
  const SimplifiedRule s = simplify_quadrature(r.points, r.weights, m, o);
  ASSERT_TRUE(s.simplified) << s.message;
  EXPECT_EQ(s.method, "simplex");
  EXPECT_NE(s.message.find("active set stopped after 1 iterations"), std::string::npos) << s.message;
  EXPECT_LE(s.size(), 20);
  EXPECT_GT(s.weights.minCoeff(), 0.0);
  EXPECT_LE(s.moment_residual, 2e-15);
}

// N <= M: nothing to gain, the input comes back unchanged and says so.
TEST(QuadratureSimplification, SmallRuleIsReturnedUnchanged) {
  const QuadratureRule& tet = quadrature_rule(CellType::Tetrahedron, 2);  // 4 points, M = 10
  const SimplifiedRule s = simplify_quadrature(tet.points, tet.weights, 2);
  EXPECT_FALSE(s.simplified);
  EXPECT_FALSE(s.message.empty());
  EXPECT_EQ(s.points, tet.points);
  EXPECT_EQ(s.weights, tet.weights);
  EXPECT_EQ(s.points_before, tet.size());
  EXPECT_EQ(s.basis_size, 10);
}

TEST(QuadratureSimplification, BadInputThrowsNamingTheArgument) {
  const Eigen::MatrixXd x = Eigen::MatrixXd::Random(3, 30);
  const Eigen::VectorXd w = Eigen::VectorXd::Constant(30, 0.1);
  auto message = [](const std::function<void()>& f) -> std::string {
    try {
      f();
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "no exception";
  };
  EXPECT_NE(message([&] { simplify_quadrature(x, w, -1); }).find("degree"), std::string::npos);
  EXPECT_NE(message([&] { simplify_quadrature(x, w.head(29), 2); }).find("weights has 29"), std::string::npos);
  EXPECT_NE(message([&] { simplify_quadrature(x.topRows(2), w, 2); }).find("points must have 3 rows"), std::string::npos);
  Eigen::VectorXd neg = w;
  neg[7] = -1e-3;
  EXPECT_NE(message([&] { simplify_quadrature(x, neg, 2); }).find("weights[7]"), std::string::npos);
  Eigen::VectorXd nan_w = w;
  nan_w[3] = std::nan("");
  EXPECT_NE(message([&] { simplify_quadrature(x, nan_w, 2); }).find("weights[3]"), std::string::npos);
  Eigen::MatrixXd nan_x = x;
  nan_x(1, 4) = std::nan("");
  EXPECT_NE(message([&] { simplify_quadrature(nan_x, w, 2); }).find("points contain"), std::string::npos);
}

// The header promises concurrent calls are safe (GLPK built with thread-local
// environments): two threads simplifying at once get the serial result bit for bit.
TEST(QuadratureSimplification, ConcurrentCallsGiveTheSerialResult) {
  const Rule a = tet_subdivided_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1), 2, 3);
  const Rule b = tet_subdivided_box(Eigen::Vector3d(-1, 0, 0), Eigen::Vector3d(0, 0.5, 2), 2, 5);
  const SimplifiedRule sa = simplify_quadrature(a.points, a.weights, 3);
  const SimplifiedRule sb = simplify_quadrature(b.points, b.weights, 5);
  ASSERT_TRUE(sa.simplified && sb.simplified);
  SimplifiedRule ta[4], tb[4];
  std::thread t1([&] {
    for (auto& s : ta) s = simplify_quadrature(a.points, a.weights, 3);
  });
  std::thread t2([&] {
    for (auto& s : tb) s = simplify_quadrature(b.points, b.weights, 5);
  });
  t1.join();
  t2.join();
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(ta[i].points, sa.points);
    EXPECT_EQ(ta[i].weights, sa.weights);
    EXPECT_EQ(tb[i].points, sb.points);
    EXPECT_EQ(tb[i].weights, sb.weights);
  }
}

}  // namespace
}  // namespace hofem

namespace hofem {
namespace {

// The clipped degree-m rule of the twisting-cylinder scene's tube (r 0.5 to 1,
// height 3, 1 x 16 x 8 cells of 6 tets) over the box [lo, hi]: a real cut cell,
// thousands of points on a curved wall.
Rule tube_cell_rule(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int m) {
  const std::vector<Tetrahedron> tets =
      mesh_tetrahedra(hollow_cylinder_mesh(0.5, 1.0, 3.0, 1, 16, 8, CellType::Tetrahedron, 1));
  const PhysicalRule p = box_cell_rule(tets, BoxBucketGrid(bounding_boxes(tets)), lo, hi, m);
  Rule r{Eigen::MatrixXd(3, p.size()), Eigen::VectorXd(p.size())};
  for (int q = 0; q < p.size(); ++q) {
    r.points.col(q) = p.points[q];
    r.weights[q] = p.weights[q];
  }
  return r;
}

// Largest |Q_1(f) - Q_0(f)| / Q_0(|f|) over the monomials f = u^a v^b w^c with
// a + b + c = the given degrees, u = (x - lo) / (hi - lo) per axis, in long double.
double monomial_difference(const Rule& r0, const Eigen::MatrixXd& x1, const Eigen::VectorXd& w1,
                           const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int min_degree, int max_degree) {
  double worst = 0.0;
  for (int a = 0; a <= max_degree; ++a)
    for (int b = 0; a + b <= max_degree; ++b)
      for (int c = 0; a + b + c <= max_degree; ++c) {
        if (a + b + c < min_degree) continue;
        auto f = [&](const Eigen::Vector3d& x) {
          const Eigen::Vector3d u = (x - lo).cwiseQuotient(hi - lo);
          return std::pow(static_cast<long double>(u.x()), a) * std::pow(static_cast<long double>(u.y()), b) *
                 std::pow(static_cast<long double>(u.z()), c);
        };
        long double q0 = 0.0L, q0_abs = 0.0L, q1 = 0.0L;
        for (Eigen::Index j = 0; j < r0.weights.size(); ++j) {
          q0 += r0.weights[j] * f(r0.points.col(j));
          q0_abs += std::fabs(r0.weights[j] * f(r0.points.col(j)));
        }
        for (Eigen::Index j = 0; j < w1.size(); ++j) q1 += w1[j] * f(x1.col(j));
        worst = std::max(worst, static_cast<double>(std::fabs(q1 - q0) / q0_abs));
      }
  return worst;
}

// The fast path (CholeskyQR2 and an updated QR) reaches the reference path's
// answer: the same points, bit for bit and in the same order (the active set's
// iterates are invariant under an orthogonal change of its constraints, so only
// rounding separates the two), and the same moments to rounding. Cut cells of the
// cylinder scene at the stiffness degrees of Hex8 and Hex20 (4, 6), ~1e3-1e4 points.
TEST(QuadratureSimplification, FastPathKeepsTheReferencePoints) {
  const std::pair<Eigen::Vector3d, Eigen::Vector3d> boxes[] = {
      {{0.0, 0.0, 0.0}, {1.0, 1.0, 1.5}}, {{-1.0, 0.0, 1.5}, {0.0, 1.0, 3.0}}, {{0.5, -0.5, 0.0}, {1.0, 0.0, 0.75}}};
  int compared = 0;
  for (const auto& [lo, hi] : boxes)
    for (int m : {4, 6}) {
      const Rule r = tube_cell_rule(lo, hi, m);
      ASSERT_GT(r.weights.size(), 10 * polynomial_space_dimension(m));
      SimplificationOptions reference;
      reference.fast = false;
      const SimplifiedRule s0 = simplify_quadrature(r.points, r.weights, m, reference);
      const SimplifiedRule s1 = simplify_quadrature(r.points, r.weights, m);
      ASSERT_TRUE(s0.simplified && s1.simplified) << s0.message << " / " << s1.message;
      EXPECT_FALSE(s0.fast);
      EXPECT_TRUE(s1.fast) << s1.message;  // the fast path answered, not its fallback
      EXPECT_EQ(s1.points, s0.points) << "m = " << m;
      // Both keep the moments to their residual (<= 1e-15 of the weights' sum in
      // the Chebyshev basis); in monomials of the box coordinates (|f| <= 1 on the
      // points) that is ~1e-15 of Q_0(|f|) for low degrees and up to ~1e-13 for
      // the smallest degree-6 monomials, whose Q_0(|f|) is ~1e-2 of the volume:
      // 1e-12 leaves a margin of 10.
      EXPECT_LE(monomial_difference(r, s1.points, s1.weights, lo, hi, 0, m), 1e-12) << "m = " << m;
      EXPECT_LE(s1.moment_residual, 1e-14);
      ++compared;
    }
  EXPECT_EQ(compared, 6);
}

// Moment fitting keeps every moment of degree <= m (here m = 8, the Hex20 mass
// degree) with C(m+3, 3) points, and no more: degree m + 1 is visibly off, so
// the first bound is not met by a rule that merely copies the input. Bounds: the
// fitted weights' |w| sum stays within a few times the volume (measured <= 2.4 on
// the cylinder's cut cells), so the monomials agree to the rounding of the
// moments (~1e-15 relative to the sum of |w0 f|) times that and the fitting
// matrix's conditioning (fitting_condition, checked below): 1e-12.
TEST(QuadratureSimplification, MomentFittingKeepsEveryMomentUpToItsDegree) {
  const int m = 8, M = polynomial_space_dimension(m);
  EXPECT_LT(fitting_condition(m), 1e3);
  const std::pair<Eigen::Vector3d, Eigen::Vector3d> boxes[] = {{{0.0, 0.0, 0.0}, {1.0, 1.0, 1.5}},
                                                               {{0.5, -0.5, 0.0}, {1.0, 0.0, 0.75}}};
  for (const auto& [lo, hi] : boxes) {
    const Rule r = tube_cell_rule(lo, hi, m);
    const FittedRule f = fit_quadrature(r.points, r.weights, m);
    ASSERT_TRUE(f.fitted) << f.message;
    EXPECT_EQ(f.size(), M);
    EXPECT_LE(f.moment_residual, 1e-14);
    EXPECT_LE(f.absolute_weight_ratio, 10.0);
    EXPECT_LE(monomial_difference(r, f.points, f.weights, lo, hi, 0, m), 1e-12);
    EXPECT_GT(monomial_difference(r, f.points, f.weights, lo, hi, m + 1, m + 1), 1e-6);
    // The points stay in the input's bounding box (inside the cell).
    const Eigen::Vector3d a = r.points.rowwise().minCoeff(), b = r.points.rowwise().maxCoeff();
    for (int q = 0; q < f.size(); ++q)
      EXPECT_TRUE((f.points.col(q).array() >= a.array()).all() && (f.points.col(q).array() <= b.array()).all());
  }
  // Nothing to fit: N <= M returns the input.
  const Rule small = tet_subdivided_box({0, 0, 0}, {1, 1, 1}, 1, 2);
  EXPECT_FALSE(fit_quadrature(small.points, small.weights, m).fitted);
}

}  // namespace
}  // namespace hofem
