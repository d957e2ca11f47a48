#include "mesh/mesh.hpp"
#include "basis/element_orders.hpp"

#include <fmt/format.h>

namespace hofem {

const std::vector<int>& Mesh::node_set(const std::string& name) const {
  const auto it = node_sets.find(name);
  if (it != node_sets.end()) return it->second;
  std::string names;
  for (const auto& [n, _] : node_sets) names += (names.empty() ? "" : ", ") + n;
  throw MeshError(fmt::format("no node set '{}' (available: {})", name, names.empty() ? "none" : names));
}

std::string describe_element(const Mesh& mesh, int e) {
  const MeshSource& src = mesh.source;
  const auto k = static_cast<std::size_t>(e);
  if (src.file.empty() || k >= src.element_tags.size()) return fmt::format("element {}", e);
  if (k < src.element_lines.size()) return fmt::format("{}:{}: element {}", src.file, src.element_lines[k], src.element_tags[k]);
  return fmt::format("{}: element {}", src.file, src.element_tags[k]);
}

int nodes_per_element(CellType cell, int order) {
  if (cell == CellType::Tetrahedron) {
    if (order < 1) throw MeshError(fmt::format("tetrahedron order must be >= 1, got {}", order));
    return (order + 1) * (order + 2) * (order + 3) / 6;
  }
  if (cell == CellType::Hexahedron) {
    if (!supports_order(cell, order))
      throw MeshError(fmt::format("hexahedra support {}, got {}", supported_orders(cell), order));
    return order == 1 ? 8 : 20;
  }
  // Triangles: surfaces written for output (the embedded surface of the finite cell method).
  if (cell == CellType::Triangle && order >= 1) return (order + 1) * (order + 2) / 2;
  throw MeshError(fmt::format("meshes of {} cells are not supported (tet or hex)", name(cell)));
}

}  // namespace hofem
