#include "embedded/finite_cell_quadrature.hpp"

#include "embedded/embedded_quadrature.hpp"
#include "quadrature/rule_library.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace hofem {

CellQuadrature finite_cell_quadrature(const Mesh& background, std::span<const Tetrahedron> geometry, int degree) {
  if (background.cell != CellType::Hexahedron)
    throw std::invalid_argument("finite_cell_quadrature: the background must be a Hex8/Hex20 grid");
  const TetBucketGrid grid(geometry);
  CellQuadrature out;
  out.rules.resize(background.num_elements());
  out.volume_fraction.assign(background.num_elements(), 0.0);
  for (int e = 0; e < background.num_elements(); ++e) {
    Eigen::Matrix<double, 3, 8> corners;
    for (int i = 0; i < 8; ++i) corners.col(i) = background.nodes.col(background.elements(i, e));
    const Eigen::Vector3d lo = corners.rowwise().minCoeff(), hi = corners.rowwise().maxCoeff();
    const Eigen::Vector3d size = hi - lo;
    // Axis-aligned box: every corner sits on a corner of its bounding box.
    for (int i = 0; i < 8; ++i)
      for (int k = 0; k < 3; ++k)
        if (std::min(std::abs(corners(k, i) - lo[k]), std::abs(corners(k, i) - hi[k])) > 1e-12 * size.norm())
          throw std::invalid_argument(fmt::format(
              "finite_cell_quadrature: element {} is not an axis-aligned box (non-affine cells are not supported)", e));
    const PhysicalRule r = box_cell_rule(geometry, grid, lo, hi, degree);
    out.points += r.size();
    // x = lo + (xi + 1) / 2 * size  =>  xi = 2 (x - lo) / size - 1, dx = size.prod() / 8 dxi.
    Eigen::MatrixXd xi(3, r.size());
    Eigen::VectorXd w(r.size());
    const double scale = 8.0 / size.prod();
    for (int q = 0; q < r.size(); ++q) {
      xi.col(q) = 2.0 * (r.points[q] - lo).cwiseQuotient(size) - Eigen::Vector3d::Ones();
      w[q] = r.weights[q] * scale;
    }
    out.volume_fraction[e] = r.volume() / size.prod();
    out.rules[e] = std::make_shared<const ElementQuadrature>(
        make_element_quadrature(CellType::Hexahedron, background.order, std::move(xi), std::move(w)));
  }
  return out;
}

StabilisedCells stabilise_finite_cells(const Mesh& background, CellQuadrature& cells,
                                       const FiniteCellStabilisation& options) {
  if (!(options.drop_fraction >= 0.0 && options.drop_fraction < 1.0) || !(options.stabilisation >= 0.0))
    throw std::invalid_argument("stabilise_finite_cells: needs 0 <= drop_fraction < 1 and stabilisation >= 0");
  if (cells.rules.size() != static_cast<size_t>(background.num_elements()))
    throw std::invalid_argument("stabilise_finite_cells: the rules are not those of this background mesh");
  const QuadratureRule& gauss = quadrature_rule(
      CellType::Hexahedron, options.gauss_degree >= 0 ? options.gauss_degree : 2 * background.order);
  StabilisedCells out;
  const Eigen::MatrixXd no_points(3, 0);
  for (int e = 0; e < background.num_elements(); ++e) {
    const double f = cells.volume_fraction[e];
    if (f <= 0.0 || f >= 1.0 - 1e-12) continue;  // empty or uncut
    if (f < options.drop_fraction) {
      cells.rules[e] = std::make_shared<const ElementQuadrature>(
          make_element_quadrature(CellType::Hexahedron, background.order, no_points, Eigen::VectorXd()));
      out.dropped.push_back(e);
      continue;
    }
    if (options.stabilisation == 0.0) continue;
    const QuadratureRule& cut = cells.rules[e]->rule;
    Eigen::MatrixXd points(3, cut.size() + gauss.size());
    Eigen::VectorXd weights(cut.size() + gauss.size());
    points << cut.points, gauss.points;
    weights << cut.weights, options.stabilisation * gauss.weights;
    cells.rules[e] = std::make_shared<const ElementQuadrature>(
        make_element_quadrature(CellType::Hexahedron, background.order, std::move(points), std::move(weights)));
    out.stabilised.push_back(e);
  }
  return out;
}

std::vector<int> active_nodes(const Mesh& background, const CellQuadrature& cells) {
  std::vector<char> used(background.num_nodes(), 0);
  for (int e = 0; e < background.num_elements(); ++e)
    if (cells.rules[e] && cells.rules[e]->rule.size() > 0)
      for (int i = 0; i < background.nodes_per_element(); ++i) used[background.elements(i, e)] = 1;
  std::vector<int> nodes;
  for (int n = 0; n < background.num_nodes(); ++n)
    if (used[n]) nodes.push_back(n);
  return nodes;
}

}  // namespace hofem
