#include "quadrature/gauss_rules.hpp"

#include "quadrature/gauss_jacobi.hpp"

#include <fmt/format.h>

#include <stdexcept>
#include <vector>

namespace hofem {

namespace {

struct Rule1D {
  std::vector<double> x, w;
};

// Computed in long double (64-bit mantissa) and rounded: ~1 ulp in double.
Rule1D jacobi_1d(int n, int alpha) {
  std::vector<long double> x, w;
  detail::gauss_jacobi<long double>(n, alpha, 0, x, w);
  Rule1D r;
  r.x.assign(x.begin(), x.end());
  r.w.assign(w.begin(), w.end());
  return r;
}

void require_points(int n) {
  if (n < 1) throw std::invalid_argument(fmt::format("Gauss rule: need at least 1 point, got {}", n));
}

}  // namespace

int gauss_points_for_degree(int degree) {
  if (degree < 0) throw std::invalid_argument(fmt::format("quadrature degree must be >= 0, got {}", degree));
  return degree / 2 + 1;
}

QuadratureRule gauss_jacobi(int n, int alpha) {
  require_points(n);
  const Rule1D r = jacobi_1d(n, alpha);
  QuadratureRule q;
  q.cell = CellType::Segment;
  q.degree = 2 * n - 1;
  q.family = RuleFamily::GaussTensor;
  q.source = fmt::format("Gauss-Jacobi alpha={} n={} (Golub-Welsch + Newton, long double)", alpha, n);
  q.id = fmt::format("gauss-jacobi{}-n{}", alpha, n);
  q.claimed_quality = "PI";
  q.points = Eigen::Map<const Eigen::RowVectorXd>(r.x.data(), n);
  q.weights = Eigen::Map<const Eigen::VectorXd>(r.w.data(), n);
  return q;
}

QuadratureRule gauss_legendre(int n) {
  QuadratureRule q = gauss_jacobi(n, 0);
  q.source = fmt::format("Gauss-Legendre n={} (Newton on Legendre polynomials, long double)", n);
  q.id = fmt::format("gauss-legendre-n{}", n);
  return q;
}

QuadratureRule gauss_tensor(CellType cell, int n) {
  require_points(n);
  if (cell == CellType::Segment) return gauss_legendre(n);
  if (cell != CellType::Quadrilateral && cell != CellType::Hexahedron)
    throw std::invalid_argument(fmt::format("gauss_tensor: {} is not a tensor-product cell", name(cell)));
  const Rule1D r = jacobi_1d(n, 0);
  const int d = dimension(cell);
  const int total = d == 2 ? n * n : n * n * n;
  QuadratureRule q;
  q.cell = cell;
  q.degree = 2 * n - 1;
  q.family = RuleFamily::GaussTensor;
  q.source = fmt::format("tensor Gauss-Legendre {}^{}", n, d);
  q.id = fmt::format("gauss-tensor-n{}", n);
  q.claimed_quality = "PI";
  q.points.resize(d, total);
  q.weights.resize(total);
  int k = 0;
  const int nz = d == 3 ? n : 1;
  for (int c = 0; c < nz; ++c)
    for (int b = 0; b < n; ++b)
      for (int a = 0; a < n; ++a, ++k) {
        q.points(0, k) = r.x[a];
        q.points(1, k) = r.x[b];
        double w = r.w[a] * r.w[b];
        if (d == 3) {
          q.points(2, k) = r.x[c];
          w *= r.w[c];
        }
        q.weights[k] = w;
      }
  return q;
}

QuadratureRule gauss_collapsed(CellType cell, int degree) {
  if (cell != CellType::Triangle && cell != CellType::Tetrahedron)
    throw std::invalid_argument(fmt::format("gauss_collapsed: {} is not a simplex", name(cell)));
  const int n = gauss_points_for_degree(degree);
  const int d = dimension(cell);
  // 1D rules mapped from [-1,1] to [0,1]: t -> (1+t)/2. With (1-v) = (1-t)/2 the
  // weight (1-v)^alpha dv becomes (1-t)^alpha dt / 2^(alpha+1).
  const Rule1D gu = jacobi_1d(n, 0), gv = jacobi_1d(n, 1);
  const Rule1D gw = d == 3 ? jacobi_1d(n, 2) : Rule1D{{0.0}, {1.0}};
  const int total = d == 2 ? n * n : n * n * n;
  QuadratureRule q;
  q.cell = cell;
  q.degree = 2 * n - 1;
  q.family = RuleFamily::GaussCollapsed;
  q.source = fmt::format("collapsed Gauss-Jacobi (Stroud conical product), {} points per direction", n);
  q.id = fmt::format("collapsed-n{}", n);
  q.claimed_quality = "PI";
  q.points.resize(d, total);
  q.weights.resize(total);
  int k = 0;
  const int nw = d == 3 ? n : 1;
  for (int c = 0; c < nw; ++c)
    for (int b = 0; b < n; ++b)
      for (int a = 0; a < n; ++a, ++k) {
        const double u = 0.5 * (1.0 + gu.x[a]);
        const double v = 0.5 * (1.0 + gv.x[b]);
        double wt = gu.w[a] / 2.0 * gv.w[b] / 4.0;
        if (d == 2) {
          q.points(0, k) = u * (1.0 - v);
          q.points(1, k) = v;
        } else {
          const double w = 0.5 * (1.0 + gw.x[c]);
          q.points(0, k) = u * (1.0 - v) * (1.0 - w);
          q.points(1, k) = v * (1.0 - w);
          q.points(2, k) = w;
          wt *= gw.w[c] / 8.0;
        }
        q.weights[k] = wt;
      }
  return q;
}

QuadratureRule gauss_rule_for_degree(CellType cell, int degree) {
  if (cell == CellType::Triangle || cell == CellType::Tetrahedron) return gauss_collapsed(cell, degree);
  return gauss_tensor(cell, gauss_points_for_degree(degree));
}

}  // namespace hofem
