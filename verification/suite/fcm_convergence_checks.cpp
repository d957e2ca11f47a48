// Longva et al. 2020 Fig. 10 (§6.6): static L2 convergence of the finite cell method
// on a hemisphere-like body in hex grids, against conforming FEM on the same
// grid, which cannot follow the curved boundary.
//
// Where Longva et al. 2020 measure against a fine boundary-conforming reference, we use a
// manufactured solution, so the error is exact: u* of manufactured_solution.hpp
// (linear elasticity, E = 1, nu = 0.3), body force f = -Div P(u*), u = u* on the
// background nodes of the flat face z = 0 (a grid plane), and on the curved
// surface the traction t = P(u*) n integrated over the embedded surface's
// triangles, clipped by the background cells (embedded_surface_quadrature.hpp;
// a rule over whole triangles integrates the basis' kinks and stalls the error,
// see there). The body is the polyhedron of its tet mesh (half_ball.hpp), so u*
// solves the continuous problem on it exactly and the L2 error over it is
// measured with its own cut-cell rules.
//
// Staircase FEM "on the same grid": the cells with volume fraction >= 1/2 with
// standard rules (boundary-fitted to the grid, not to the body), given the same
// load functional (body force and surface traction of the true body); its error
// is measured over body ∩ its cells. Its geometry error is O(h) in volume, so
// it cannot keep up with FCM, and its rate is erratic (cells enter and leave the
// staircase as h changes), so only the Hex20 rate is held below O(h^3).
#include "fcm_convergence_checks.hpp"

#include "assembly/assembler.hpp"
#include "embedded/embedded_points.hpp"
#include "embedded/embedded_quadrature.hpp"
#include "embedded/embedded_surface_quadrature.hpp"
#include "embedded/finite_cell_quadrature.hpp"
#include "half_ball.hpp"
#include "study/manufactured_solution.hpp"
#include "material/material.hpp"
#include "mesh/box_mesh.hpp"
#include "problem/static_elasticity.hpp"
#include "quadrature/rule_library.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace hofem::verification {

namespace {

struct Solution {
  double l2 = 0.0;  ///< relative L2 error over the measured region
  int dofs = 0;
  double seconds = 0.0;  ///< loads, solve and error (the grid's quadrature not included)
  double residual_over_tolerance = 0.0;  ///< Newton's final |g| / (rtol * force scale): <= 1 converged
  double rtol = 0.0;                     ///< Newton's rtol
  std::string message;                   ///< the solve's
};

/// One background grid and its cut-cell rules (built once, shared by the FCM and
/// staircase solves on it: the staircase uses only the volume fractions and the
/// load rules).
struct Grid {
  Mesh background;
  CellQuadrature cells;
  double seconds = 0.0;  ///< building the rules (clipping, LP simplification)
};

/// The n x n x n/2 hex grid of order p over the half ball's bounding box, with its rules.
Grid make_grid(int order, int n, const std::vector<Tetrahedron>& body) {
  const auto t0 = std::chrono::steady_clock::now();
  Grid g;
  g.background = box_mesh(BoxSpec{{0, 0, 0}, {1, 1, 0.5}, {n, n, n / 2}}, CellType::Hexahedron, order);
  g.cells = finite_cell_quadrature(g.background, body);
  g.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return g;
}

/// The traction load ∫ N_i P(u*) n dA over the curved (z > 0) part of the surface,
/// with the surface rules clipped by the background cells.
Eigen::VectorXd traction_load(const Mesh& background, const Mesh& curved, const std::vector<char>& active,
                              const Material& material, const ManufacturedDisplacement& exact) {
  const EmbeddedSurfaceRule rule = embedded_surface_rule(background, curved, 2 * background.order + 2, active);
  return surface_load_vector(background, rule, [&](const Eigen::Vector3d& X, const Eigen::Vector3d& n) {
    return Eigen::Vector3d(material.stress(Eigen::Matrix3d::Identity() + exact.gradient(X)) * n);
  });
}

/// Relative L2 error of u over the cells with measure[e], with the (unstabilised)
/// cut-cell mass rules and the standard rule of degree 2p + 2 in uncut cells.
double l2_error(const Mesh& background, const CellQuadrature& cells, const std::vector<char>& measure,
                const Eigen::VectorXd& u, const ManufacturedDisplacement& exact) {
  const int degree = 2 * background.order + 2;
  const QuadratureRule& standard = quadrature_rule(background.cell, degree);
  const BasisTabulation& standard_tab = cached_tabulation(background.cell, background.order, degree);
  double e2 = 0.0, u2 = 0.0;
  for (int e = 0; e < background.num_elements(); ++e) {
    if (!measure[e]) continue;
    const auto& own = cells.mass_rules[e];
    const QuadratureRule& rule = own ? own->rule : standard;
    const BasisTabulation& tab = own ? own->tabulation : standard_tab;
    const AffineCell map = affine_cell(background, e);
    const double jac = std::abs(map.A.determinant());
    for (int q = 0; q < rule.size(); ++q) {
      Eigen::Vector3d uh = Eigen::Vector3d::Zero();
      for (int i = 0; i < background.nodes_per_element(); ++i)
        uh += tab.values(i, q) * u.segment<3>(3 * background.elements(i, e));
      const Eigen::Vector3d ue = exact.value(map.origin + map.A * rule.points.col(q));
      e2 += rule.weights[q] * jac * (uh - ue).squaredNorm();
      u2 += rule.weights[q] * jac * ue.squaredNorm();
    }
  }
  return std::sqrt(e2 / u2);
}

/// FCM (staircase = false) or staircase FEM on a grid.
Solution solve(const Grid& grid, bool staircase, const Mesh& surface) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  const Mesh& background = grid.background;
  const CellQuadrature& exact_cells = grid.cells;
  const int order = background.order;
  const auto material = make_material("linear", LameParameters::from_young_poisson(1.0, 0.3));
  const ManufacturedDisplacement exact{1.0};
  const Eigen::Matrix<double, 9, 9> A = material->stress_derivative(Eigen::Matrix3d::Identity());  // linear: constant
  const VectorField force = [&](const Eigen::Vector3d& X) {
    Eigen::Matrix3d H[3];
    exact.hessians(X, H);
    return equilibrium_body_force(A, H);
  };
  std::vector<char> measured(background.num_elements());
  for (int e = 0; e < background.num_elements(); ++e)
    measured[e] = staircase ? exact_cells.volume_fraction[e] >= 0.5 : exact_cells.volume_fraction[e] > 0.0;
  CellQuadrature solve_cells = exact_cells;
  if (staircase) {
    const auto none = std::make_shared<const ElementQuadrature>(
        make_element_quadrature(CellType::Hexahedron, order, Eigen::MatrixXd(3, 0), Eigen::VectorXd()));
    for (int e = 0; e < background.num_elements(); ++e)
      solve_cells.rules[e] = solve_cells.mass_rules[e] = measured[e] ? nullptr : none;
  } else {
    // §5.3 defaults (drop below 1e-4, 1e-6 Gauss points) on the stiffness; the mass
    // rules of a static solve carry no stiffness and stay as the loads use them.
    FiniteCellStabilisation stabilisation;
    stabilisation.mass = false;
    stabilise_finite_cells(background, solve_cells, stabilisation);
  }
  // Cells that carry stiffness in the solve: the traction's points in any other
  // cell (a dropped sliver, a cell outside the staircase) go to the nearest of them.
  std::vector<char> active(background.num_elements());
  for (int e = 0; e < background.num_elements(); ++e)
    active[e] = !solve_cells.rules[e] || solve_cells.rules[e]->rule.size() > 0;

  // The load functional of the true body: body force with the cut-cell rules, traction on its surface.
  const DofMap all(background.num_nodes(), {});
  Assembler loads(background, all);
  loads.set_element_rules(exact_cells.element_rules());
  StaticOptions o;
  o.external_load = loads.body_force_vector(force, 2 * order + 2) +
                    traction_load(background, surface, active, *material, exact);
  o.element_rules = solve_cells.element_rules();
  o.newton.rtol = 1e-10;
  std::vector<int> flat;
  for (int m = 0; m < background.num_nodes(); ++m)
    if (std::abs(background.nodes(2, m)) < 1e-12) flat.push_back(m);
  StaticElasticity problem(background, *material, {{flat, [&](const Eigen::Vector3d& X) { return exact.value(X); }}},
                           {}, o);
  const StaticReport r = problem.solve();
  Solution s;
  s.residual_over_tolerance = residual_over_tolerance(r, o.newton.rtol);
  s.rtol = o.newton.rtol;
  s.message = r.message;
  s.dofs = problem.dofs().num_free();
  s.l2 = l2_error(background, exact_cells, measured, problem.displacement(), exact);
  s.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return s;
}

}  // namespace

void add_fcm_convergence_checks(Report& report, const std::string& level) {
  const std::string group = "embedded.fig10";
  const Mesh body_mesh = half_ball(4);
  const std::vector<Tetrahedron> body = mesh_tetrahedra(body_mesh);
  const Mesh curved = half_ball_curved_surface(body_mesh);
  // Grids h = 1/n per order. The full level refines Hex8 to 1/32 but Hex20 to
  // 1/24: its rate is the same there (2.98 to 1/24 and to 1/32) while its 1/32
  // grid alone took 80 of the family's 98 s and 10 GB (cut-cell rules: 5.4M
  // points clipped, 36 s; FCM solve, 124k unknowns, 29 s; staircase 13 s).
  const auto grids_of = [&](int order) {
    if (level != "full") return std::vector<int>{4, 8};
    return order == 1 ? std::vector<int>{4, 8, 16, 32} : std::vector<int>{4, 8, 16, 24};
  };
  struct Series {
    int order;
    bool staircase;
    const char* name;
  };
  // Each grid's rules once, then its FCM and staircase solves.
  std::map<std::pair<int, bool>, std::vector<Solution>> solutions;  // (order, staircase) -> per grid
  for (int order : {1, 2})
    for (int n : grids_of(order)) {
      const Grid grid = make_grid(order, n, body);
      report.measure(group, fmt::format("{} h=1/{} cut-cell rules seconds", order == 1 ? "Hex8" : "Hex20", n),
                     grid.seconds,
                     fmt::format("clipping and simplification (§4.4): {} -> {} stiffness points, {} mass points",
                                 grid.cells.points, grid.cells.simplified_points, grid.cells.mass_points));
      for (bool staircase : {false, true}) solutions[{order, staircase}].push_back(solve(grid, staircase, curved));
    }
  std::map<std::pair<int, bool>, double> finest;  // (order, staircase) -> L2 error on the finest grid
  for (const Series& series : {Series{1, false, "FCM Hex8"}, Series{2, false, "FCM Hex20"}, Series{1, true, "staircase FEM Hex8"},
                               Series{2, true, "staircase FEM Hex20"}}) {
    const std::vector<int> grids = grids_of(series.order);
    std::vector<double> h, error;
    for (size_t k = 0; k < grids.size(); ++k) {
      const int n = grids[k];
      const Solution& s = solutions[{series.order, series.staircase}][k];
      report.measure(group, fmt::format("{} h=1/{} l2", series.name, n), s.l2,
                     fmt::format("relative L2 error; {} DOFs; {:.2f} s (loads, solve, error)", s.dofs, s.seconds));
      report.check(group, fmt::format("{} h=1/{}: solve converged", series.name, n), s.residual_over_tolerance, 1.0,
                   Compare::AtMost,
                   fmt::format("final Newton residual |g| / (rtol {:.0e} x force scale): <= 1 is Newton's stopping "
                               "rule (newton.hpp), the error is of the discrete solution only if it holds; {}",
                               s.rtol, s.message));
      h.push_back(1.0 / n);
      error.push_back(s.l2);
    }
    auto rate = [&](size_t k) { return std::log(error[k - 1] / error[k]) / std::log(h[k - 1] / h[k]); };
    const size_t last = h.size() - 1;
    const int optimal = series.order + 1;
    finest[{series.order, series.staircase}] = error[last];
    if (!series.staircase) {
      // Optimal L2 rate p + 1 (Hex8 2, Hex20 3; Longva et al.'s Fig. 10) on each of the
      // last two pairs of grids, less 0.2 / 0.3 for what is left of the
      // pre-asymptotic range (measured: Hex8 1.96, 1.98; Hex20 2.98, 2.98; the ci
      // level's 1/4 -> 1/8: 1.88, 2.96). Every measured rate approaches from below,
      // so the window is symmetric: above p + 1 + 0.2 / 0.3 the error is not the
      // L2 norm of the discrete solution's error (or u*, not polynomial, were
      // reproduced exactly), and a whole order too fast fails.
      const double window = series.order == 1 ? 0.2 : 0.3;
      for (size_t k = std::max<size_t>(1, last - 1); k <= last; ++k)
        report.check_rate(group, fmt::format("{} L2 rate h=1/{} -> 1/{}", series.name, grids[k - 1], grids[k]), rate(k),
                          optimal, window, window,
                          fmt::format("O(h^{}) expected; measured from below (1.88-1.99 Hex8, 2.96-2.98 Hex20)",
                                      optimal));
      // The error must fall on every refinement: a curve that turns upward is a defect.
      double worst = 0.0;
      for (size_t k = 1; k <= last; ++k) worst = std::max(worst, error[k] / error[k - 1]);
      report.check(group, fmt::format("{} largest error ratio of successive grids", series.name), worst, 1.0,
                   Compare::AtMost, "the error decreases monotonically under refinement");
      continue;
    }
    report.measure(group, fmt::format("{} L2 rate h=1/{} -> 1/{}", series.name, grids[last - 1], grids[last]),
                   rate(last), "erratic: which cells enter the staircase changes with h");
    const double ratio = error[last] / finest[{series.order, false}];
    // The staircase body differs from the true one by O(h) in volume, so on the
    // finest grid it is less accurate than FCM; for Hex20, whose FCM error is
    // O(h^3), by an order of magnitude (Longva et al. 2020: "dramatically reduced").
    report.check(group, fmt::format("{} / FCM L2 error on the finest grid", series.name), ratio,
                 series.order == 2 ? 10.0 : 1.0, Compare::AtLeast, "the geometry is not resolved");
    // Its rate is held below O(h^3) only where there is an asymptotic range to
    // speak of (the full level's 1/16 -> 1/24: 0.75 measured, 1.04 to 1/32); between 1/4 and 1/8
    // it swings with the cells that enter the staircase (2.59 with these loads,
    // 1.89 when the loads went to cells outside the staircase). One-sided by
    // design, unlike the FCM rates: the claim is that the O(h) geometry error
    // keeps the staircase from the optimal rate (Longva et al.: "dramatically
    // reduced"), and no rate is expected from it that a lower bound could hold.
    if (series.order == 2 && grids.size() >= 4)
      report.check(group, fmt::format("{} L2 rate h=1/{} -> 1/{}", series.name, grids[last - 1], grids[last]),
                   rate(last), optimal - 0.5, Compare::AtMost, "below O(h^3)");
  }
}

}  // namespace hofem::verification
