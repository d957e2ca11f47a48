#include "basis_checks.hpp"

#include "gmsh_node_tables.hpp"
#include "monomials.hpp"

#include "basis/simplex_lagrange_basis.hpp"

#include <fmt/format.h>

#include <cmath>
#include <random>

namespace hofem::verification {

namespace {

// Points spread over the reference cell (deterministic seed), including its vertices.
Eigen::MatrixXd sample_points(CellType cell, int count) {
  std::mt19937_64 rng(20261122);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int d = dimension(cell);
  Eigen::MatrixXd verts = reference_vertices(cell);
  Eigen::MatrixXd x(d, count + verts.cols());
  for (int k = 0; k < count; ++k) {
    if (cell == CellType::Triangle || cell == CellType::Tetrahedron) {
      // Uniform on the simplex: sorted uniforms -> spacings.
      std::vector<double> s(d);
      for (double& v : s) v = u(rng);
      std::sort(s.begin(), s.end());
      double prev = 0.0;
      for (int c = 0; c < d; ++c) {
        x(c, k) = s[c] - prev;
        prev = s[c];
      }
    } else {
      for (int c = 0; c < d; ++c) x(c, k) = 2.0 * u(rng) - 1.0;
    }
  }
  x.rightCols(verts.cols()) = verts;
  return x;
}

}  // namespace

void check_basis(Report& report, const ReferenceBasis& basis) {
  const int n = basis.size(), d = basis.dim();
  const std::string label = basis.element_name();
  // Orthonormal-basis Vandermonde with cond <~ 1e3 (see add_basis_checks): the
  // nodal values carry ~cond * eps ~ 1e-13 of rounding; 1e-12 is the bound.
  double kron = 0.0;
  for (int j = 0; j < n; ++j) {
    const Eigen::VectorXd N = basis.evaluate(basis.nodes().col(j));
    for (int i = 0; i < n; ++i) kron = std::max(kron, std::fabs(N[i] - (i == j ? 1.0 : 0.0)));
  }
  report.check("basis.kronecker", label, kron, 1e-12, Compare::AtMost, "max |N_i(x_j) - delta_ij|");

  const Eigen::MatrixXd pts = sample_points(basis.cell(), 60);
  double pu = 0.0, gsum = 0.0, gscale = 0.0;
  for (int k = 0; k < pts.cols(); ++k) {
    pu = std::max(pu, std::fabs(basis.evaluate(pts.col(k)).sum() - 1.0));
    const Eigen::MatrixXd G = basis.gradients(pts.col(k));
    gsum = std::max(gsum, G.colwise().sum().cwiseAbs().maxCoeff());
    gscale = std::max(gscale, G.cwiseAbs().maxCoeff());
  }
  report.check("basis.partition_of_unity", label, pu, 1e-12, Compare::AtMost, "max |sum_i N_i(x) - 1| at 60 points + vertices");
  // Gradients are O(p^2) in size; relative to the largest |dN/dxi| the sum is at rounding level.
  report.check("basis.gradient_sum", label, gsum / gscale, 1e-13, Compare::AtMost,
               "max |sum_i grad N_i(x)| / max |grad N_i|");

  // Reproduction: interpolate each monomial of the basis' space from its nodal values.
  double rep = 0.0, rep_grad = 0.0;
  for (const Exponent& e : basis.polynomial_space()) {
    Eigen::VectorXd nodal(n);
    for (int i = 0; i < n; ++i) nodal[i] = monomial(basis.nodes().col(i).data(), d, e);
    for (int k = 0; k < pts.cols(); ++k) {
      const double* x = pts.col(k).data();
      rep = std::max(rep, std::fabs(basis.evaluate(pts.col(k)).dot(nodal) - monomial(x, d, e)));
      const Eigen::VectorXd g = basis.gradients(pts.col(k)).transpose() * nodal;
      for (int c = 0; c < d; ++c) {
        Exponent de = e;
        double exact = 0.0;
        if (de[c] > 0) {
          const double coef = de[c];
          --de[c];
          exact = coef * monomial(x, d, de);
        }
        rep_grad = std::max(rep_grad, std::fabs(g[c] - exact));
      }
    }
  }
  report.check("basis.reproduction", label, rep, 1e-12, Compare::AtMost,
               "max |sum_i m(x_i) N_i(x) - m(x)| over the basis' monomial space");
  report.check("basis.reproduction_gradient", label, rep_grad / std::max(1.0, double(basis.order() * basis.order())), 1e-12,
               Compare::AtMost, "max |sum_i m(x_i) grad N_i(x) - grad m(x)| / p^2 (gradients scale with p^2)");

  // Central differences, h = 1e-5: truncation h^2/6 |N'''| <= ~2e-8 for the
  // steepest order-6 function (|N'''| ~ 1e3 measured), rounding eps/h ~ 2e-11;
  // relative to max |grad N| (>= 1) the bound 1e-7 holds with a 5x margin.
  const double h = 1e-5;
  double fd = 0.0;
  for (int k = 0; k < pts.cols() - static_cast<int>(reference_vertices(basis.cell()).cols()); ++k) {
    const Eigen::MatrixXd G = basis.gradients(pts.col(k));
    for (int c = 0; c < d; ++c) {
      Eigen::VectorXd xp = pts.col(k), xm = pts.col(k);
      xp[c] += h;
      xm[c] -= h;
      const Eigen::VectorXd diff = (basis.evaluate(xp) - basis.evaluate(xm)) / (2 * h);
      fd = std::max(fd, (diff - G.col(c)).cwiseAbs().maxCoeff());
    }
  }
  report.check("basis.gradient_fd", label, fd / gscale, 1e-7, Compare::AtMost,
               "max |central difference (h=1e-5) - grad N| / max |grad N|");
}

void add_basis_checks(Report& report) {
  for (CellType cell : {CellType::Segment, CellType::Triangle, CellType::Tetrahedron})
    for (int p = 1; p <= 6; ++p) check_basis(report, lagrange_basis(cell, p));
  check_basis(report, lagrange_basis(CellType::Hexahedron, 1));
  check_basis(report, lagrange_basis(CellType::Hexahedron, 2));

  // Node order against Gmsh's own tables (gmsh_node_tables.hpp).
  for (const GmshNodeTable& t : gmsh_node_tables()) {
    const ReferenceBasis& b = lagrange_basis(t.cell, t.order);
    double worst = b.size() == static_cast<int>(t.nodes.size()) ? 0.0 : 1.0;
    for (size_t i = 0; i < t.nodes.size() && worst < 1.0; ++i)
      for (int c = 0; c < b.dim(); ++c) worst = std::max(worst, std::fabs(b.nodes()(c, i) - t.nodes[i][c]));
    report.check("basis.gmsh_node_order", fmt::format("{} vs Gmsh {}", b.element_name(), t.name), worst, 1e-15,
                 Compare::AtMost, "max |node - Gmsh reference node| (1 if the node count differs)");
  }

  // Conditioning: the orthonormal Vandermonde stays small; the thesis' monomial one grows.
  for (CellType cell : {CellType::Triangle, CellType::Tetrahedron})
    for (int p = 1; p <= 10; ++p) {
      const SimplexLagrangeBasis basis(cell, p);
      const std::string label = fmt::format("{} order {}", name(cell), p);
      report.check("basis.vandermonde_condition", label, basis.vandermonde_condition(), 1e4, Compare::AtMost,
                   "cond_2(V) of the Dubiner Vandermonde: <= 1e4 keeps nodal values to ~1e-12");
      report.measure("basis.vandermonde_condition_monomial", label, monomial_vandermonde_condition(cell, p),
                     "cond_2 of the thesis' monomial Vandermonde (eq. 4.28/4.34) on the same nodes");
    }
}

}  // namespace hofem::verification
