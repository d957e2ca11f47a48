#include "embedded/finite_cell_quadrature.hpp"

#include "embedded/embedded_quadrature.hpp"

#include <fmt/format.h>

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

}  // namespace hofem
