// The load functional on cut cells (finite cell method): the consistent loads of
// a body force (cut cells' mass/load rules, Assembler::body_force_vector) and of
// a surface traction (embedded_surface_rule, clipped by the background cells),
// as assembled for the half ball of the Fig. 10 check, held against the exact
// work they must do on displacement fields of the background space:
//
//  1. v polynomial (each component of total degree p, so its interpolant is v
//     itself): b_f . v = ∫_B f . v dV and b_t . v = ∫_Γ t . v dA for a quadratic
//     body force f and t = σ(X) n with σ linear in X. The reference integrates
//     over the body's own tets and surface triangles, without the background.
//  2. v with random nodal values: piecewise polynomial, with kinks on every cell
//     face. For a symmetric σ(X), linear in X, the divergence theorem gives
//     ∫_∂B (σ n) . v dA = ∫_B (Div σ) . v dV + ∫_B σ : ∇v dV: the traction's load
//     against the body force f = Div σ's load plus the volume term, integrated
//     with the cut cells' own stiffness rules (exact for σ : ∇v in each cell).
//     Rules that ignore the cell faces (one rule per surface triangle, or per
//     embedded tet) integrate the kinks and break this identity; measured with
//     one rule per surface triangle: 8e-6 to 4e-4 instead of <= 6e-16.
//
// Every integrand is a polynomial of a degree the rules integrate exactly, so
// the only error is rounding: relative to the sum of |terms| (~1e4 points, each
// term exact to ~1e-16), 1e-12 leaves a margin of 10-100 above what rounding makes.
#include "fcm_load_checks.hpp"

#include "assembly/assembler.hpp"
#include "basis/reference_basis.hpp"
#include "embedded/embedded_points.hpp"
#include "embedded/embedded_quadrature.hpp"
#include "embedded/embedded_surface_quadrature.hpp"
#include "embedded/finite_cell_quadrature.hpp"
#include "half_ball.hpp"
#include "mesh/box_mesh.hpp"
#include "quadrature/rule_library.hpp"

#include <fmt/format.h>

#include <cmath>
#include <random>

namespace hofem::verification {

namespace {

constexpr double kRounding = 1e-12;  // see the top of the file

/// A polynomial vector field of total degree `degree` with fixed coefficients.
struct PolynomialField {
  int degree = 1;
  Eigen::Vector3d operator()(const Eigen::Vector3d& X) const {
    const double x = X.x(), y = X.y(), z = X.z();
    Eigen::Vector3d v(0.3 + 0.7 * x - 0.2 * y + 0.5 * z, -0.4 + 0.1 * x + 0.9 * y - 0.3 * z, 0.2 - 0.6 * x + 0.4 * y + 0.8 * z);
    if (degree >= 2) v += Eigen::Vector3d(0.5 * x * y - 0.3 * z * z, 0.7 * x * x + 0.2 * y * z, -0.4 * y * y + 0.6 * x * z);
    return v;
  }
};

/// Div σ of stress(X, true) below, by hand: row i of d/dX_j of the linear part
/// (0.6 x, 0.2 z, -0.3 y; 0.2 z, 0.5 y, 0.1 x; -0.3 y, 0.1 x, -0.4 z).
const Eigen::Vector3d kStressDivergence(0.6, 0.5, -0.4);

/// Quadratic body force.
Eigen::Vector3d body_force(const Eigen::Vector3d& X) {
  const double x = X.x(), y = X.y(), z = X.z();
  return {1.0 + 0.5 * x * x - 0.3 * y * z, -0.7 + 0.8 * x * y + 0.2 * z, 0.4 - 0.6 * z * z + 0.9 * x};
}

/// A symmetric stress, linear in X (constant if `linear` is false).
Eigen::Matrix3d stress(const Eigen::Vector3d& X, bool linear) {
  Eigen::Matrix3d s;
  s << 1.0, 0.3, -0.2, 0.3, -0.5, 0.4, -0.2, 0.4, 0.8;
  if (linear) {
    Eigen::Matrix3d d;
    d << 0.6 * X.x(), 0.2 * X.z(), -0.3 * X.y(), 0.2 * X.z(), 0.5 * X.y(), 0.1 * X.x(), -0.3 * X.y(), 0.1 * X.x(),
        -0.4 * X.z();
    s += d;
  }
  return s;
}

Eigen::VectorXd nodal_values(const Mesh& mesh, const PolynomialField& v) {
  Eigen::VectorXd u(3 * mesh.num_nodes());
  for (int n = 0; n < mesh.num_nodes(); ++n) u.segment<3>(3 * n) = v(mesh.nodes.col(n));
  return u;
}

/// Relative difference of a work and its reference, against the sum of |terms| of the reference.
double relative(double got, double exact, double scale) { return std::abs(got - exact) / scale; }

/// ∫_B σ(X) : ∇v dV (σ = stress(X, true)) with the cut cells' stiffness rules and
/// standard rules in uncut cells; also the sum of |terms|.
std::pair<double, double> volume_work(const Mesh& background, const CellQuadrature& cells, const Eigen::VectorXd& u) {
  const int degree = 2 * background.order;
  const QuadratureRule& standard = quadrature_rule(background.cell, degree);
  const BasisTabulation& standard_tab = cached_tabulation(background.cell, background.order, degree);
  double work = 0.0, scale = 0.0;
  for (int e = 0; e < background.num_elements(); ++e) {
    if (!(cells.volume_fraction[e] > 0.0)) continue;
    const auto& own = cells.rules[e];
    const QuadratureRule& rule = own ? own->rule : standard;
    const BasisTabulation& tab = own ? own->tabulation : standard_tab;
    const AffineCell map = affine_cell(background, e);
    const double jac = std::abs(map.A.determinant());
    for (int q = 0; q < rule.size(); ++q) {
      Eigen::Matrix3d grad = Eigen::Matrix3d::Zero();  // (i, j) = d v_i / d X_j
      const auto g = tab.gradient(q);
      for (int a = 0; a < background.nodes_per_element(); ++a)
        grad += u.segment<3>(3 * background.elements(a, e)) * (g.row(a) * map.A_inverse);
      const Eigen::Vector3d X = map.origin + map.A * rule.points.col(q);
      const double term = rule.weights[q] * jac * (stress(X, true).cwiseProduct(grad)).sum();
      work += term;
      scale += std::abs(term);
    }
  }
  return {work, scale};
}

void check_background(Report& report, const Mesh& body_mesh, const Mesh& surface, const Mesh& curved, int order, int n) {
  const std::string group = "embedded.loads";
  const std::string label = fmt::format("{} h=1/{}", order == 1 ? "Hex8" : "Hex20", n);
  const Mesh background = box_mesh(BoxSpec{{0, 0, 0}, {1, 1, 0.5}, {n, n, n / 2}}, CellType::Hexahedron, order);
  FiniteCellOptions fo;
  fo.simplify = false;  // the loads use the unsimplified rules; the simplification is checked by Fig. 4
  const CellQuadrature cells = finite_cell_quadrature(background, mesh_tetrahedra(body_mesh), fo);
  int cut = 0;
  for (double f : cells.volume_fraction) cut += f > 0.0 && f < 1.0 - 1e-12;
  const int degree = 2 * order + 2;  // the Fig. 10 check's load degree
  const PolynomialField v{order};
  const Eigen::VectorXd v_nodal = nodal_values(background, v);

  // 1a. Body force against the body's tets (a degree-6 rule: f . v has degree <= 4).
  const DofMap all(background.num_nodes(), {});
  Assembler assembler(background, all);
  assembler.set_element_rules(cells.element_rules());
  const double body_got = assembler.body_force_vector(body_force, degree).dot(v_nodal);
  const QuadratureRule& tet_rule = quadrature_rule(CellType::Tetrahedron, 6);
  double body_exact = 0.0, body_scale = 0.0;
  for (const Tetrahedron& t : mesh_tetrahedra(body_mesh)) {
    Eigen::Matrix3d J;
    J << t.v.col(1) - t.v.col(0), t.v.col(2) - t.v.col(0), t.v.col(3) - t.v.col(0);
    for (int q = 0; q < tet_rule.size(); ++q) {
      const Eigen::Vector3d X = t.v.col(0) + J * tet_rule.points.col(q);
      const double term = std::abs(J.determinant()) * tet_rule.weights[q] * body_force(X).dot(v(X));
      body_exact += term;
      body_scale += std::abs(term);
    }
  }
  report.check(group, fmt::format("{}: body-force work on a degree-{} field", label, order),
               relative(body_got, body_exact, body_scale), kRounding, Compare::AtMost,
               fmt::format("|b_f.v - int f.v| / int |f.v|; {} cut cells; exact rules, rounding only", cut));

  // 1b. Traction t = σ(X) n on the curved surface against its triangles (degree 6: t . v has degree <= 3).
  const EmbeddedSurfaceRule curved_rule = embedded_surface_rule(background, curved, degree);
  const SurfaceTraction linear_traction = [](const Eigen::Vector3d& X, const Eigen::Vector3d& nrm) -> Eigen::Vector3d {
    return stress(X, true) * nrm;
  };
  const double traction_got = surface_load_vector(background, curved_rule, linear_traction).dot(v_nodal);
  const QuadratureRule& tri_rule = quadrature_rule(CellType::Triangle, 6);
  double traction_exact = 0.0, traction_scale = 0.0;
  for (int t = 0; t < curved.num_elements(); ++t) {
    const Eigen::Vector3d a = curved.nodes.col(curved.elements(0, t)), b = curved.nodes.col(curved.elements(1, t)),
                          c = curved.nodes.col(curved.elements(2, t));
    const Eigen::Vector3d n2 = (b - a).cross(c - a);
    for (int q = 0; q < tri_rule.size(); ++q) {
      const Eigen::Vector3d X = a + (b - a) * tri_rule.points(0, q) + (c - a) * tri_rule.points(1, q);
      const double term = n2.norm() * tri_rule.weights[q] * linear_traction(X, n2.normalized()).dot(v(X));
      traction_exact += term;
      traction_scale += std::abs(term);
    }
  }
  report.check(group, fmt::format("{}: traction work on a degree-{} field", label, order),
               relative(traction_got, traction_exact, traction_scale), kRounding, Compare::AtMost,
               fmt::format("|b_t.v - int t.v| / int |t.v| over the curved surface; {} surface points", curved_rule.size()));

  // 2. A field with kinks on every cell face: the divergence theorem on the closed surface.
  std::mt19937_64 rng(20201);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Eigen::VectorXd kinked(3 * background.num_nodes());
  for (Eigen::Index i = 0; i < kinked.size(); ++i) kinked[i] = uniform(rng);
  const EmbeddedSurfaceRule closed_rule = embedded_surface_rule(background, surface, degree);
  const double surface_side = surface_load_vector(background, closed_rule, linear_traction).dot(kinked);
  const double body_side =
      assembler.body_force_vector([](const Eigen::Vector3d&) { return kStressDivergence; }, degree).dot(kinked);
  const auto [volume_side, volume_scale] = volume_work(background, cells, kinked);
  report.check(group, fmt::format("{}: divergence theorem on a field with kinks at the cell faces", label),
               relative(surface_side, body_side + volume_side, volume_scale), kRounding, Compare::AtMost,
               "|b_t.v - b_f.v - int_B sigma:grad v| / int |sigma:grad v|; f = Div sigma, random nodal v; exact per cell");
}

}  // namespace

void add_fcm_load_checks(Report& report) {
  const Mesh body_mesh = half_ball(4);
  const Mesh surface = boundary_surface(body_mesh);
  const Mesh curved = half_ball_curved_surface(body_mesh);
  for (int order : {1, 2})
    for (int n : {6, 10}) check_background(report, body_mesh, surface, curved, order, n);
}

}  // namespace hofem::verification
