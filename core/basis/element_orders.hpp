#pragma once
// Which element orders each cell supports - the one home of "hex: order 1
// (Hex8) or 2 (Hex20), tet: any order" - and the family names the seeds use
// (Tet4, Tet10, Tet20, Hex8, Hex20). Simplices take any order >= 1 (Lagrange
// bases over Dubiner polynomials); the input cap on the order
// (io/input_file.hpp) bounds them apart from this rule. Hexahedra have Hex8
// and the 20-node serendipity Hex20 only. One table: element_orders.cpp.
#include "quadrature/cell_type.hpp"

#include <string>

namespace hofem {

/// The highest order a cell's elements support (a large number for simplices:
/// no limit of their own); 0 for cells without volume elements (quadrilateral).
int max_element_order(CellType cell);
/// order >= 1 and <= max_element_order(cell).
bool supports_order(CellType cell, int order);
/// "1 (Hex8) or 2 (Hex20)" / "any order >= 1": what error messages say.
std::string supported_orders(CellType cell);
/// Throws std::invalid_argument "<what>: <cell> supports <supported_orders>, got <order>"
/// unless supports_order(cell, order).
void check_element_order(CellType cell, int order, const std::string& what);
/// The family's name, as Gmsh and the seeds write it: "Tet10", "Hex20", "Tri6".
std::string element_family_name(CellType cell, int order);

}  // namespace hofem
