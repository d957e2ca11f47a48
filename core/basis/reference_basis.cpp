#include "basis/reference_basis.hpp"

#include "basis/hex_bases.hpp"
#include "basis/simplex_lagrange_basis.hpp"
#include "basis/element_orders.hpp"

#include <fmt/format.h>

#include <map>
#include <mutex>
#include <stdexcept>

namespace hofem {

std::unique_ptr<ReferenceBasis> make_lagrange_basis(CellType cell, int order) {
  switch (cell) {
    case CellType::Segment:
    case CellType::Triangle:
    case CellType::Tetrahedron: return std::make_unique<SimplexLagrangeBasis>(cell, order);
    case CellType::Hexahedron:
      check_element_order(cell, order, "hex basis");
      if (order == 1) return std::make_unique<Hex8Basis>();
      return std::make_unique<Hex20Basis>();
    case CellType::Quadrilateral: break;
  }
  throw std::invalid_argument(fmt::format("no Lagrange basis for cell {}", name(cell)));
}

const ReferenceBasis& lagrange_basis(CellType cell, int order) {
  static std::mutex mutex;
  static std::map<std::pair<int, int>, std::unique_ptr<ReferenceBasis>> bases;
  std::lock_guard<std::mutex> lock(mutex);
  auto& slot = bases[{static_cast<int>(cell), order}];
  if (!slot) slot = make_lagrange_basis(cell, order);
  return *slot;
}

}  // namespace hofem
