#pragma once
// The one place that answers "which rule for this cell and degree?".
//
// Tabulated rules (published symmetric data and the thesis' Hammer rules) cover
// the triangle and tetrahedron up to degree 20; beyond that, and on the segment,
// quad and hex, Gauss rules of any degree are built on demand. A query returns
// the fewest-point rule exact to at least the requested degree, preferring rules
// whose weights are all positive and points all strictly inside (measured, not
// taken from labels). Rules are built once and cached; references stay valid for
// the life of the program and the cache is safe to use from several threads.
#include "quadrature/quadrature_rule.hpp"

#include <vector>

namespace hofem {

/// Best rule for (cell, degree), see above. degree >= 0; throws std::invalid_argument otherwise.
const QuadratureRule& quadrature_rule(CellType cell, int degree);

/// Every tabulated rule of a cell (published + Hammer), in data order; empty for
/// tensor cells. Includes rules the query would never pick (negative weights,
/// boundary points) so that the test suite can check them all.
const std::vector<QuadratureRule>& tabulated_rules(CellType cell);

/// Highest degree covered by tabulated rules on a cell (0 if none).
int max_tabulated_degree(CellType cell);

}  // namespace hofem
