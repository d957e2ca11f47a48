#include "quadrature_checks.hpp"

#include "monomials.hpp"

#include "basis/simplex_orthonormal_basis.hpp"
#include "quadrature/gauss_jacobi.hpp"
#include "quadrature/gauss_rules.hpp"
#include "quadrature/rule_library.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>

namespace hofem::verification {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// Exactness bound of the issue: relative error <= 1e-13. Rounding of a rule with
// n points contributes ~sqrt(n) eps relative to the integral of |m| (< 1e-14 for
// the largest rule checked, 4096 points), so 1e-13 leaves a 10x margin and
// still catches any wrong digit in the data beyond the 13th.
constexpr double kExactness = 1e-13;
// A rule "fails" at degree + 1 if some orthonormal polynomial of that degree is
// integrated with an error 1000x above the exactness bound.
constexpr double kSharpness = 1e-10;
// Smallest weight of a rule the query returns, relative to its mean weight
// |cell| / n: 100 eps, far above the rounding of a weight (~eps of the mean) and far
// below the smallest weight of a returned rule (measured: 1.1e-6, the tet's
// collapsed-n16 at degree 30, whose corner points carry the Jacobi weights' ends).
constexpr double kPositiveWeight = 100 * kEps;

double normalised_legendre(int k, double x) {
  return std::sqrt((2.0 * k + 1.0) / 2.0) * detail::jacobi_polynomial<double>(k, 0, 0, x);
}

}  // namespace

double max_monomial_error(const QuadratureRule& rule, int max_degree) {
  const int d = rule.dim();
  double worst = 0.0;
  for (int deg = 0; deg <= max_degree; ++deg)
    for (const Exponent& e : monomials_of_degree(d, deg)) {
      long double q = 0.0L;
      for (int i = 0; i < rule.size(); ++i) q += rule.weights[i] * monomial(rule.points.col(i).data(), d, e);
      const long double err = std::fabs(q - exact_monomial_integral(rule.cell, e)) / abs_monomial_integral(rule.cell, e);
      worst = std::max(worst, static_cast<double>(err));
    }
  return worst;
}

double orthonormal_error(const QuadratureRule& rule, int degree) {
  const double scale = std::sqrt(reference_volume(rule.cell));
  double worst = 0.0;
  if (rule.cell == CellType::Triangle || rule.cell == CellType::Tetrahedron) {
    const OrthonormalSimplexBasis psi(rule.cell, degree);
    std::vector<double> v(psi.size()), sums(psi.size(), 0.0);
    for (int i = 0; i < rule.size(); ++i) {
      psi.evaluate(rule.points.col(i).data(), v.data(), nullptr);
      for (int m = 0; m < psi.size(); ++m) sums[m] += rule.weights[i] * v[m];
    }
    for (int m = 0; m < psi.size(); ++m)
      if (psi.degree_of(m) == degree) worst = std::max(worst, std::fabs(sums[m]) / scale);
    return worst;
  }
  // Tensor cells: products of normalised Legendre polynomials of total degree `degree`.
  for (const Exponent& e : monomials_of_degree(rule.dim(), degree)) {
    double s = 0.0;
    for (int i = 0; i < rule.size(); ++i) {
      double v = 1.0;
      for (int c = 0; c < rule.dim(); ++c) v *= normalised_legendre(e[c], rule.points(c, i));
      s += rule.weights[i] * v;
    }
    worst = std::max(worst, std::fabs(s) / scale);
  }
  return worst;
}

void check_rule(Report& report, const QuadratureRule& rule) {
  const std::string label = fmt::format("{} {} (n={}, degree {})", name(rule.cell), rule.id, rule.size(), rule.degree);
  report.check("quadrature.exactness", label, max_monomial_error(rule, rule.degree), kExactness, Compare::AtMost,
               "max over monomials of degree <= claimed: |Q-I| / integral|m|");
  report.check("quadrature.sharpness", label, orthonormal_error(rule, rule.degree + 1), kSharpness, Compare::AtLeast,
               "claimed degree is the true one: some orthonormal polynomial of degree+1 is not integrated");
  const double vol = reference_volume(rule.cell);
  const double sum_err = std::fabs(rule.weights.sum() - vol) / vol;
  // Summation of n rounded weights: error <= n eps (and >= eps for n = 1).
  report.check("quadrature.weight_sum", label, sum_err, std::max(1.0, double(rule.size())) * kEps, Compare::AtMost,
               "|sum w - |cell|| / |cell| <= n eps (rounding of n weights)");
  const std::string& q = rule.claimed_quality;
  if (q.find('P') != std::string::npos)
    report.check("quadrature.positivity", label, rule.min_weight(), std::numeric_limits<double>::min(), Compare::AtLeast,
                 "claimed positive: min weight > 0");
  if (q.find('N') != std::string::npos)
    report.check("quadrature.positivity", label, rule.min_weight(), -std::numeric_limits<double>::min(), Compare::AtMost,
                 "claimed to have a negative weight (so the query must skip it)");
  if (q.find('I') != std::string::npos)
    report.check("quadrature.interior", label, rule.min_interior_margin(), kInteriorTolerance, Compare::AtLeast,
                 "claimed interior: min barycentric / box margin > 1e-12 (kInteriorTolerance)");
  if (q.find('B') != std::string::npos)
    report.check("quadrature.interior", label, std::fabs(rule.min_interior_margin()), kInteriorTolerance, Compare::AtMost,
                 "claimed to have boundary points: min margin == 0 to 1e-12 (so the query must skip it)");
}

namespace {

double ulp_distance(long double reference, double value) {
  const double r = static_cast<double>(reference);
  const double ulp = std::nextafter(std::fabs(r), std::numeric_limits<double>::infinity()) - std::fabs(r);
  return static_cast<double>(std::fabs(static_cast<long double>(value) - reference) / ulp);
}

void add_gauss_legendre_checks(Report& report) {
  for (int n = 1; n <= 64; ++n) {
    const QuadratureRule rule = gauss_legendre(n);
    check_rule(report, rule);
    // Reference in quadruple precision (113-bit mantissa), rounded to long double
    // for the comparison (64-bit mantissa: 11 bits finer than double's ulp).
    std::vector<__float128> xq, wq;
    detail::gauss_jacobi<__float128>(n, 0, 0, xq, wq);
    double worst_x = 0.0, worst_w = 0.0;
    for (int i = 0; i < n; ++i) {
      if (xq[i] != 0) worst_x = std::max(worst_x, ulp_distance(static_cast<long double>(xq[i]), rule.points(0, i)));
      else worst_x = std::max(worst_x, rule.points(0, i) == 0.0 ? 0.0 : 1e9);
      worst_w = std::max(worst_w, ulp_distance(static_cast<long double>(wq[i]), rule.weights[i]));
    }
    const std::string label = fmt::format("gauss-legendre n={}", n);
    report.check("quadrature.gauss_legendre_ulp", label + " nodes", worst_x, 1.0, Compare::AtMost,
                 "max |x - x_quad| in ulps of double against a __float128 computation");
    report.check("quadrature.gauss_legendre_ulp", label + " weights", worst_w, 1.0, Compare::AtMost,
                 "max |w - w_quad| in ulps of double against a __float128 computation");
  }
}

// Best published symmetric positive-interior point counts, degrees 1..20
// (shared/quadrature-sources.md: WV15 for the triangle; WV15 <= 10 and CCGV22
// above for the tetrahedron). The query may only do better (rotationally
// symmetric rules such as Papanicolopulos 2016 are smaller).
constexpr int kTriangleSymmetric[21] = {0, 1, 3, 6, 6, 7, 12, 15, 16, 19, 25, 28, 33, 37, 42, 49, 55, 60, 67, 73, 79};
constexpr int kTetSymmetric[21] = {0, 1, 4, 8, 14, 14, 24, 35, 46, 59, 81, 98, 123, 145, 175, 209, 248, 284, 343, 383, 441};

// What the query promises of the rule it returns, measured: exact to the
// requested degree (the quadrature.exactness measure at that degree), positive
// weights and interior points, each beyond round-off.
void check_query_rule(Report& report, const std::string& label, const QuadratureRule& r, int degree) {
  report.check("quadrature.query", label + " exactness at the requested degree", max_monomial_error(r, degree),
               kExactness, Compare::AtMost,
               fmt::format("max over monomials of degree <= {} (requested; the rule claims {}): |Q-I| / integral|m|, "
                           "1e-13 as quadrature.exactness",
                           degree, r.degree));
  const double mean_weight = r.weights.sum() / r.size();
  report.check("quadrature.query", label + " min weight / mean weight", r.min_weight() / mean_weight, kPositiveWeight,
               Compare::AtLeast,
               "positive beyond round-off: a weight's own rounding is ~eps of the mean weight |cell| / n, so 100 eps "
               "separates a positive weight from a zero one that rounded up (smallest returned: 1.1e-6)");
  report.check("quadrature.query", label + " min barycentric coordinate", r.min_interior_margin(), kInteriorTolerance,
               Compare::AtLeast,
               "interior beyond round-off: 1e-12 (kInteriorTolerance, quadrature_rule.hpp) separates points stored on "
               "the boundary (~1e-16) from interior ones (closest returned: 1.0e-6, CCGV22-19-383)");
}

void add_query_checks(Report& report) {
  for (CellType cell : {CellType::Triangle, CellType::Tetrahedron}) {
    for (int degree = 1; degree <= 30; ++degree) {
      const QuadratureRule& r = quadrature_rule(cell, degree);
      const std::string label = fmt::format("{} degree {} -> {} (n={})", name(cell), degree, r.id, r.size());
      check_query_rule(report, label, r, degree);
      report.measure("quadrature.points_query", fmt::format("{} {}", name(cell), degree), r.size(), r.id);
      report.measure("quadrature.points_collapsed", fmt::format("{} {}", name(cell), degree),
                     gauss_collapsed(cell, degree).size(), "Stroud conical product rule of the same degree");
      if (degree <= 20) {
        const int best = cell == CellType::Triangle ? kTriangleSymmetric[degree] : kTetSymmetric[degree];
        report.check("quadrature.query", label + " points beyond the best published", r.size() - best, 0,
                     Compare::AtMost,
                     fmt::format("n = {} against {}: no more than the best published symmetric PI rule "
                                 "(quadrature-sources.md)",
                                 r.size(), best));
      }
    }
  }
  for (CellType cell : {CellType::Segment, CellType::Quadrilateral, CellType::Hexahedron})
    for (int degree : {1, 2, 5, 9, 15}) {
      const QuadratureRule& r = quadrature_rule(cell, degree);
      const int n1 = gauss_points_for_degree(degree);
      const int expected = cell == CellType::Segment ? n1 : cell == CellType::Quadrilateral ? n1 * n1 : n1 * n1 * n1;
      report.check("quadrature.query",
                   fmt::format("{} degree {} -> {} (n={}) points beyond tensor Gauss", name(cell), degree, r.id, r.size()),
                   r.size() - expected, 0, Compare::AtMost,
                   fmt::format("n = {} against {}: tensor Gauss with ceil((p+1)/2) points per direction", r.size(),
                               expected));
    }
}

}  // namespace

void add_quadrature_checks(Report& report) {
  add_gauss_legendre_checks(report);
  for (int n = 1; n <= 10; ++n) {
    check_rule(report, gauss_tensor(CellType::Quadrilateral, n));
    check_rule(report, gauss_tensor(CellType::Hexahedron, n));
  }
  for (CellType cell : {CellType::Triangle, CellType::Tetrahedron}) {
    for (int degree = 1; degree <= 31; degree += 2) check_rule(report, gauss_collapsed(cell, degree));
    for (const QuadratureRule& rule : tabulated_rules(cell)) check_rule(report, rule);
  }
  add_query_checks(report);
}

}  // namespace hofem::verification
