#include "distributed/local_mesh.hpp"

#include "distributed/mesh_partition.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace hofem {

int LocalMesh::owned_nodes() const {
  return static_cast<int>(std::count(owner.begin(), owner.end(), part));
}

LocalMesh extract_part(const Mesh& global, const std::vector<int>& part, int p) {
  if (static_cast<int>(part.size()) != global.num_elements())
    throw std::invalid_argument(
        fmt::format("extract_part: {} part labels for a mesh of {} elements", part.size(), global.num_elements()));
  LocalMesh local;
  local.part = p;
  local.global_nodes = global.num_nodes();
  local.global_elements = global.num_elements();
  for (int e = 0; e < global.num_elements(); ++e)
    if (part[e] == p) local.global_element.push_back(e);
  if (local.global_element.empty()) throw std::invalid_argument(fmt::format("extract_part: part {} has no elements", p));
  // Local numbering: the touched nodes in ascending global order.
  std::vector<int> local_of(global.num_nodes(), -1);
  for (int e : local.global_element)
    for (int i = 0; i < global.nodes_per_element(); ++i) local_of[global.elements(i, e)] = 0;
  for (int n = 0; n < global.num_nodes(); ++n)
    if (local_of[n] == 0) {
      local_of[n] = static_cast<int>(local.global_node.size());
      local.global_node.push_back(n);
    }
  const std::vector<int> owner = node_owners(global, part);
  Mesh& m = local.mesh;
  m.cell = global.cell;
  m.order = global.order;
  m.nodes = global.nodes(Eigen::all, local.global_node);
  for (const std::int64_t n : local.global_node) local.owner.push_back(owner[n]);
  m.elements = global.elements(Eigen::all, local.global_element).unaryExpr([&](int n) { return local_of[n]; });
  for (const auto& [name, nodes] : global.node_sets) {
    std::vector<int>& mine = m.node_sets[name];
    for (int n : nodes)
      if (n >= 0 && n < global.num_nodes() && local_of[n] >= 0) mine.push_back(local_of[n]);  // stays sorted
  }
  std::vector<int> local_element(global.num_elements(), -1);
  for (size_t k = 0; k < local.global_element.size(); ++k) local_element[local.global_element[k]] = static_cast<int>(k);
  for (const auto& [name, elements] : global.element_sets) {
    std::vector<int>& mine = m.element_sets[name];
    for (int e : elements)
      if (e >= 0 && e < global.num_elements() && local_element[e] >= 0) mine.push_back(local_element[e]);
  }
  return local;
}

std::vector<int> to_local_nodes(const LocalMesh& local, const std::vector<int>& global_nodes) {
  std::vector<int> out;
  for (int n : global_nodes) {
    const auto it = std::lower_bound(local.global_node.begin(), local.global_node.end(), static_cast<std::int64_t>(n));
    if (it != local.global_node.end() && *it == n) out.push_back(static_cast<int>(it - local.global_node.begin()));
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace hofem
