#include "quadrature/quadrature_rule.hpp"

#include <algorithm>
#include <limits>

namespace hofem {

std::string_view name(RuleFamily family) {
  switch (family) {
    case RuleFamily::GaussTensor: return "gauss-tensor";
    case RuleFamily::GaussCollapsed: return "gauss-collapsed";
    case RuleFamily::Hammer: return "hammer";
    case RuleFamily::Published: return "published";
  }
  return "unknown";
}

double QuadratureRule::min_interior_margin() const {
  double m = std::numeric_limits<double>::infinity();
  for (int q = 0; q < size(); ++q) m = std::min(m, interior_margin(cell, points.col(q)));
  return m;
}

}  // namespace hofem
