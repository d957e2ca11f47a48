#include "basis/element_orders.hpp"

#include <fmt/format.h>

#include <array>
#include <limits>
#include <stdexcept>

namespace hofem {

namespace {

constexpr int kAnyOrder = std::numeric_limits<int>::max();

// The element families, one row per cell: the orders its Lagrange elements
// support and what they are. Simplices: Lagrange bases over Dubiner
// polynomials of any order (basis/simplex_lagrange_basis.hpp); hexahedra: the
// trilinear Hex8 and the 20-node serendipity Hex20 (basis/hex_bases.hpp).
// Quadrilaterals have no Lagrange elements (rules only).
struct FamilyRow {
  CellType cell;
  int max_order;
  std::string_view orders;
};

constexpr std::array<FamilyRow, 5> kFamilies{{
    {CellType::Segment, kAnyOrder, "any order >= 1"},
    {CellType::Triangle, kAnyOrder, "any order >= 1"},
    {CellType::Tetrahedron, kAnyOrder, "any order >= 1"},
    {CellType::Hexahedron, 2, "order 1 (Hex8) or 2 (Hex20)"},
    {CellType::Quadrilateral, 0, "no Lagrange elements"},
}};

const FamilyRow& row(CellType cell) {
  for (const FamilyRow& r : kFamilies)
    if (r.cell == cell) return r;
  throw std::logic_error("element_orders: unknown CellType");
}

}  // namespace

int max_element_order(CellType cell) { return row(cell).max_order; }

bool supports_order(CellType cell, int order) { return order >= 1 && order <= max_element_order(cell); }

std::string supported_orders(CellType cell) { return std::string(row(cell).orders); }

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
