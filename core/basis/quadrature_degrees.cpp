#include "basis/quadrature_degrees.hpp"

#include <algorithm>

#include "basis/element_orders.hpp"
#include "basis/reference_basis.hpp"

namespace hofem {

int highest_total_degree(CellType cell, int order) {
  int d = 0;
  for (const auto& a : lagrange_basis(cell, order).polynomial_space()) d = std::max(d, a[0] + a[1] + a[2]);
  return d;
}

QuadratureDegrees default_quadrature_degrees(CellType cell, int order, IntegrationDomain domain) {
  check_element_order(cell, order, "default_quadrature_degrees");
  const bool simplex = cell != CellType::Hexahedron;
  QuadratureDegrees q;
  q.load = 2 * order + 2;
  q.mass = 2 * order;
  q.stiffness = 2 * order;
  if (domain == IntegrationDomain::Affine && simplex) q.stiffness = std::max(1, 2 * (order - 1));
  if (domain == IntegrationDomain::CutCell) {
    const int d = highest_total_degree(cell, order);
    q.stiffness = simplex ? 2 * order : 2 * (d - 1);
    q.mass = 2 * d;
  }
  return q;
}

}  // namespace hofem
