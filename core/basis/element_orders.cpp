#include "basis/element_orders.hpp"

#include <fmt/format.h>

#include <limits>
#include <stdexcept>

namespace hofem {

int max_element_order(CellType cell) {
  switch (cell) {
    case CellType::Segment:
    case CellType::Triangle:
    case CellType::Tetrahedron:
      return std::numeric_limits<int>::max();
    case CellType::Hexahedron:
      return 2;  // Hex8 and the serendipity Hex20 (basis/hex_bases.hpp)
    case CellType::Quadrilateral:
      return 0;
  }
  return 0;
}

bool supports_order(CellType cell, int order) { return order >= 1 && order <= max_element_order(cell); }

std::string supported_orders(CellType cell) {
  if (cell == CellType::Hexahedron) return "order 1 (Hex8) or 2 (Hex20)";
  if (max_element_order(cell) == 0) return "no Lagrange elements";
  return "any order >= 1";
}

void check_element_order(CellType cell, int order, const std::string& what) {
  if (!supports_order(cell, order))
    throw std::invalid_argument(
        fmt::format("{}: {} supports {}, got {}", what, name(cell), supported_orders(cell), order));
}

std::string element_family_name(CellType cell, int order) {
  check_element_order(cell, order, "element family");
  switch (cell) {
    case CellType::Segment:
      return fmt::format("Line{}", order + 1);
    case CellType::Triangle:
      return fmt::format("Tri{}", (order + 1) * (order + 2) / 2);
    case CellType::Tetrahedron:
      return fmt::format("Tet{}", (order + 1) * (order + 2) * (order + 3) / 6);
    case CellType::Hexahedron:
      return order == 1 ? "Hex8" : "Hex20";
    case CellType::Quadrilateral:
      break;
  }
  throw std::logic_error("element_family_name: unreachable");
}

}  // namespace hofem
