#pragma once
// Hammer (Hammer–Marlowe–Stroud 1956 / Radon 1948) rules of the thesis appendix,
// Tables 4 (triangle) and 5 (tetrahedron), in closed form.
#include "quadrature/quadrature_rule.hpp"

#include <vector>

namespace hofem {

/// All Hammer rules on the triangle (1, 3, 4, 7 points) or tetrahedron (1, 4, 5 points).
std::vector<QuadratureRule> hammer_rules(CellType cell);

}  // namespace hofem
