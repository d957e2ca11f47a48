#include "embedded/finite_cell_quadrature.hpp"

#include "basis/reference_basis.hpp"
#include "embedded/embedded_quadrature.hpp"
#include "embedded/quadrature_simplification.hpp"
#include "quadrature/rule_library.hpp"
#include "basis/quadrature_degrees.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

namespace hofem {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

std::shared_ptr<const ElementQuadrature> make_rule(CellType cell, int order, Eigen::MatrixXd xi, Eigen::VectorXd w) {
  return std::make_shared<const ElementQuadrature>(make_element_quadrature(cell, order, std::move(xi), std::move(w)));
}

std::shared_ptr<const ElementQuadrature> empty_rule(CellType cell, int order) {
  return make_rule(cell, order, Eigen::MatrixXd(3, 0), Eigen::VectorXd());
}

// The clipped rule of one cell at `degree`, in reference coordinates: w_ref = w / |det A| (eq. 11-12).
// Both finite_cell_quadrature and finite_cell_volume_fractions sum these weights in this order,
// so the volume fractions they report agree to the last bit.
std::pair<Eigen::MatrixXd, Eigen::VectorXd> clipped_reference_rule(std::span<const Tetrahedron> geometry,
                                                                   const std::vector<int>& candidates,
                                                                   const std::vector<HalfSpace>& planes,
                                                                   const AffineCell& map, int degree) {
  const double jac = std::abs(map.A.determinant());
  PhysicalRule r;
  for (int k : candidates) add_clipped_rule(geometry[k], planes, degree, r);
  Eigen::MatrixXd xi(3, r.size());
  Eigen::VectorXd w(r.size());
  for (int q = 0; q < r.size(); ++q) {
    const Eigen::Vector3d x = map.reference(r.points[q]);
    // Component by component: GCC 12 reports a false -Warray-bounds on the
    // AVX-512 packet copy of a Vector3d into a dynamic matrix's column.
    for (int k = 0; k < 3; ++k) xi(k, q) = x[k];
    w[q] = r.weights[q] / jac;
  }
  return {std::move(xi), std::move(w)};
}

// The geometry's tetrahedra that may meet background cell e (bounding boxes).
std::vector<int> cell_candidates(const Mesh& background, int e, const BoxBucketGrid& grid) {
  const Eigen::Matrix3Xd vertices =
      background.nodes(Eigen::all, background.elements.col(e).head(background.vertices_per_element()));
  return grid.candidates(vertices.rowwise().minCoeff(), vertices.rowwise().maxCoeff());
}

void check_background(const Mesh& background) {
  if (background.cell != CellType::Tetrahedron && background.cell != CellType::Hexahedron)
    throw std::invalid_argument("finite_cell_quadrature: the background must be a tetrahedral or hexahedral mesh");
}

}  // namespace

double reference_cell_volume(CellType cell) { return cell == CellType::Tetrahedron ? 1.0 / 6.0 : 8.0; }

// The clipped rules integrate constants exactly, so an uncut cell's fraction is 1
// to rounding (~1e-15 relative); 1e-12 leaves room and no real cut is that thin.
bool finite_cell_cut(double f) { return f > 0.0 && f < 1.0 - 1e-12; }

bool finite_cell_dropped(double f, double drop_fraction) { return finite_cell_cut(f) && f < drop_fraction; }

AffineFit fit_affine_cell(const Mesh& mesh, int e) {
  // Least-squares fit of X = origin + A xi over all nodes; the misfit says
  // whether every node lies on it (straight-sided higher-order cells and
  // parallelepipeds do).
  const Eigen::MatrixXd& ref = lagrange_basis(mesh.cell, mesh.order).nodes();
  const int n = mesh.nodes_per_element();
  Eigen::MatrixXd B(n, 4), X(n, 3);
  for (int i = 0; i < n; ++i) {
    B(i, 0) = 1.0;
    B.block<1, 3>(i, 1) = ref.col(i).transpose();
    X.row(i) = mesh.nodes.col(mesh.elements(i, e)).transpose();
  }
  const Eigen::MatrixXd C = (B.transpose() * B).ldlt().solve(B.transpose() * X);  // 4 x 3
  AffineFit fit;
  fit.map.origin = C.row(0).transpose();
  fit.map.A = C.bottomRows(3).transpose();
  fit.size = (X.colwise().maxCoeff() - X.colwise().minCoeff()).norm();
  fit.misfit = (B * C - X).cwiseAbs().maxCoeff();
  fit.affine = fit.misfit <= 1e-10 * fit.size;
  fit.degenerate = !(std::abs(fit.map.A.determinant()) > 1e-12 * std::pow(fit.size, 3));
  if (!fit.degenerate) fit.map.A_inverse = fit.map.A.inverse();
  return fit;
}

AffineCell affine_cell(const Mesh& mesh, int e) {
  const AffineFit fit = fit_affine_cell(mesh, e);
  if (!fit.affine)
    throw std::invalid_argument(fmt::format(
        "finite cell: background element {} is not affine (node misfit {:.3g} of size {:.3g}); curved cells are not supported",
        e, fit.misfit, fit.size));
  if (fit.degenerate)
    throw std::invalid_argument(fmt::format("finite cell: background element {} is degenerate (det J = {:.3g})", e,
                                            fit.map.A.determinant()));
  return fit.map;
}

std::vector<HalfSpace> cell_half_spaces(CellType cell, const AffineCell& map) {
  // Reference inequality a . xi <= b becomes (A^-T a) . X <= b + (A^-T a) . origin.
  std::vector<HalfSpace> h;
  auto add = [&](const Eigen::Vector3d& a, double b) {
    const Eigen::Vector3d n = map.A_inverse.transpose() * a;
    h.push_back({n, b + n.dot(map.origin)});
  };
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d ek = Eigen::Vector3d::Unit(k);
    if (cell == CellType::Tetrahedron) {
      add(-ek, 0.0);  // xi_k >= 0
    } else {
      add(ek, 1.0);
      add(-ek, 1.0);
    }
  }
  if (cell == CellType::Tetrahedron) add(Eigen::Vector3d::Ones(), 1.0);
  return h;
}

CellQuadrature finite_cell_quadrature(const Mesh& background, std::span<const Tetrahedron> geometry,
                                      const FiniteCellOptions& options) {
  check_background(background);
  const CellType cell = background.cell;
  const int p = background.order, ne = background.num_elements();
  CellQuadrature out;
  const QuadratureDegrees degrees = default_quadrature_degrees(cell, p, IntegrationDomain::CutCell);
  out.stiffness_degree = options.stiffness_degree >= 0 ? options.stiffness_degree : degrees.stiffness;
  out.mass_degree = options.mass_degree >= 0 ? options.mass_degree : degrees.mass;
  std::vector<AffineCell> maps;
  maps.reserve(ne);
  for (int e = 0; e < ne; ++e) maps.push_back(affine_cell(background, e));  // throws before any work

  const auto t0 = Clock::now();
  const BoxBucketGrid grid(bounding_boxes(geometry));
  out.rules.resize(ne);
  out.mass_rules.resize(ne);
  out.volume_fraction.assign(ne, 0.0);
  out.points_before.assign(ne, 0);
  out.points_after.assign(ne, 0);
  out.moment_residual.assign(ne, 0.0);
  std::vector<double> lp_seconds(ne, 0.0), gen_seconds(ne, 0.0);
  std::vector<char> failed(ne, 0), fit_failed(ne, 0);
  std::vector<int> mass_clipped(ne, 0);
  std::vector<double> fit_residual(ne, 0.0), fit_ratio(ne, 0.0);
  const double reference_volume = reference_cell_volume(cell);

  // Cells are independent; dynamic schedule because cut cells cost far more.
#pragma omp parallel for schedule(dynamic, 4)
  for (int e = 0; e < ne; ++e) {
    const auto tc = Clock::now();
    const AffineCell& map = maps[e];
    const std::vector<HalfSpace> planes = cell_half_spaces(cell, map);
    const std::vector<int> candidates = cell_candidates(background, e, grid);
    // Clipped rules of both strengths, in reference coordinates.
    auto clipped = [&](int degree) { return clipped_reference_rule(geometry, candidates, planes, map, degree); };
    auto [xs, ws] = clipped(out.stiffness_degree);
    const double fraction = ws.sum() / reference_volume;
    out.volume_fraction[e] = fraction;
    if (ws.size() == 0) out.rules[e] = out.mass_rules[e] = empty_rule(cell, p);
    if (ws.size() == 0 || (options.standard_rule_inside && !finite_cell_cut(fraction))) {  // uncut: standard rules (null)
      gen_seconds[e] = seconds_since(tc);
      continue;
    }
    auto [xm, wm] = clipped(out.mass_degree);
    mass_clipped[e] = static_cast<int>(wm.size());
    if (options.fit_mass) {
      FittedRule f = fit_quadrature(xm, wm, out.mass_degree);
      // Accepted at the LP's own bound (SimplificationOptions::max_moment_residual).
      if (f.fitted && f.moment_residual <= 1e-11) {
        xm = std::move(f.points);
        wm = std::move(f.weights);
        fit_residual[e] = f.moment_residual;
        fit_ratio[e] = f.absolute_weight_ratio;
      } else {
        fit_failed[e] = f.fitted;
      }
    }
    gen_seconds[e] = seconds_since(tc);
    out.points_before[e] = static_cast<int>(ws.size());
    const auto tl = Clock::now();
    if (options.simplify) {
      SimplifiedRule s = simplify_quadrature(xs, ws, out.stiffness_degree, options.simplification);
      failed[e] = !s.simplified && s.points_before > s.basis_size;  // N <= M is returned as is, not a failure
      out.moment_residual[e] = s.moment_residual;
      if (s.simplified) {
        xs = std::move(s.points);
        ws = std::move(s.weights);
      }
    }
    lp_seconds[e] = seconds_since(tl);
    out.points_after[e] = static_cast<int>(ws.size());
    out.rules[e] = make_rule(cell, p, std::move(xs), std::move(ws));
    out.mass_rules[e] = make_rule(cell, p, std::move(xm), std::move(wm));
  }
  for (int e = 0; e < ne; ++e) {
    out.points += out.points_before[e];
    out.simplified_points += out.points_after[e];
    if (out.mass_rules[e]) out.mass_points += out.mass_rules[e]->rule.size();
    out.mass_points_clipped += mass_clipped[e];
    out.max_mass_moment_residual = std::max(out.max_mass_moment_residual, fit_residual[e]);
    out.max_mass_weight_ratio = std::max(out.max_mass_weight_ratio, fit_ratio[e]);
    out.mass_fit_failures += fit_failed[e];
    out.simplification_failures += failed[e];
    out.max_moment_residual = std::max(out.max_moment_residual, out.moment_residual[e]);
    out.simplification_seconds += lp_seconds[e];
    out.generation_seconds += gen_seconds[e];
  }
  out.wall_seconds = seconds_since(t0);
  return out;
}

CellQuadrature finite_cell_quadrature(const Mesh& background, std::span<const Tetrahedron> geometry, int degree) {
  FiniteCellOptions o;
  o.stiffness_degree = o.mass_degree = degree;
  o.simplify = false;
  o.standard_rule_inside = false;
  return finite_cell_quadrature(background, geometry, o);
}

std::vector<double> finite_cell_volume_fractions(const Mesh& background, std::span<const Tetrahedron> geometry,
                                                 const FiniteCellOptions& options) {
  check_background(background);
  const CellType cell = background.cell;
  const int ne = background.num_elements();
  const int degree = options.stiffness_degree >= 0
                         ? options.stiffness_degree
                         : default_quadrature_degrees(cell, background.order, IntegrationDomain::CutCell).stiffness;
  std::vector<AffineCell> maps;
  maps.reserve(ne);
  for (int e = 0; e < ne; ++e) maps.push_back(affine_cell(background, e));
  const BoxBucketGrid grid(bounding_boxes(geometry));
  std::vector<double> fraction(ne, 0.0);
#pragma omp parallel for schedule(dynamic, 4)
  for (int e = 0; e < ne; ++e) {
    const auto [xi, w] =
        clipped_reference_rule(geometry, cell_candidates(background, e, grid), cell_half_spaces(cell, maps[e]), maps[e], degree);
    fraction[e] = w.sum() / reference_cell_volume(cell);
  }
  return fraction;
}

std::vector<char> finite_cell_active(const std::vector<double>& volume_fraction, double drop_fraction) {
  std::vector<char> active(volume_fraction.size());
  // A cell the geometry misses (f = 0) has an empty rule, a dropped one an emptied
  // rule (stabilise_finite_cells); every other cell integrates.
  for (size_t e = 0; e < volume_fraction.size(); ++e)
    active[e] = volume_fraction[e] > 0.0 && !finite_cell_dropped(volume_fraction[e], drop_fraction);
  return active;
}

StabilisedCells stabilise_finite_cells(const Mesh& background, CellQuadrature& cells,
                                       const FiniteCellStabilisation& options) {
  if (!(options.drop_fraction >= 0.0 && options.drop_fraction < 1.0) || !(options.stabilisation >= 0.0))
    throw std::invalid_argument("stabilise_finite_cells: needs 0 <= drop_fraction < 1 and stabilisation >= 0");
  const int ne = background.num_elements();
  if (cells.rules.size() != size_t(ne) || cells.mass_rules.size() != size_t(ne) ||
      cells.volume_fraction.size() != size_t(ne))
    throw std::invalid_argument("stabilise_finite_cells: the rules are not those of this background mesh");
  const CellType cell = background.cell;
  const int p = background.order;
  const QuadratureRule& gauss =
      quadrature_rule(cell, options.gauss_degree >= 0 ? options.gauss_degree : 2 * background.order);
  auto with_gauss_points = [&](const QuadratureRule& r) {
    std::pair<Eigen::MatrixXd, Eigen::VectorXd> out{Eigen::MatrixXd(3, r.size() + gauss.size()),
                                                    Eigen::VectorXd(r.size() + gauss.size())};
    out.first << r.points, gauss.points;
    out.second << r.weights, options.stabilisation * gauss.weights;
    return out;
  };
  enum Fate : char { Untouched, Dropped, Stabilised };
  std::vector<Fate> fate(ne, Untouched);
  std::vector<char> folded(ne, 0);
  std::vector<double> lp_seconds(ne, 0.0);
  // Cells are independent; the folds' LPs make cut cells far costlier than the rest.
#pragma omp parallel for schedule(dynamic, 4)
  for (int e = 0; e < ne; ++e) {
    const double f = cells.volume_fraction[e];
    if (!finite_cell_cut(f) || !cells.rules[e]) continue;  // empty or uncut
    if (finite_cell_dropped(f, options.drop_fraction)) {
      cells.rules[e] = cells.mass_rules[e] = empty_rule(cell, p);
      fate[e] = Dropped;
      continue;
    }
    if (options.stabilisation == 0.0) continue;
    auto [xs, ws] = with_gauss_points(cells.rules[e]->rule);
    if (options.simplify_degree >= 0) {
      const auto tl = Clock::now();
      SimplifiedRule s = simplify_quadrature(xs, ws, options.simplify_degree, options.simplification);
      lp_seconds[e] = seconds_since(tl);
      if (s.simplified) {
        xs = std::move(s.points);
        ws = std::move(s.weights);
        folded[e] = 1;
      }
    }
    cells.rules[e] = make_rule(cell, p, std::move(xs), std::move(ws));
    if (options.mass && cells.mass_rules[e]) {
      auto [xm, wm] = with_gauss_points(cells.mass_rules[e]->rule);
      cells.mass_rules[e] = make_rule(cell, p, std::move(xm), std::move(wm));
    }
    fate[e] = Stabilised;
  }
  StabilisedCells out;
  for (int e = 0; e < ne; ++e) {
    if (fate[e] == Dropped) out.dropped.push_back(e);
    if (fate[e] == Stabilised) out.stabilised.push_back(e);
    out.folded += folded[e];
    out.simplification_seconds += lp_seconds[e];
  }
  return out;
}

std::vector<int> schwarz_block_elements(const CellQuadrature& cells, double threshold) {
  std::vector<int> out;
  for (size_t e = 0; e < cells.volume_fraction.size(); ++e) {
    const double f = cells.volume_fraction[e];
    const bool dropped = cells.rules[e] && cells.rules[e]->rule.size() == 0;
    if (finite_cell_cut(f) && f < threshold && !dropped) out.push_back(static_cast<int>(e));
  }
  return out;
}

}  // namespace hofem
