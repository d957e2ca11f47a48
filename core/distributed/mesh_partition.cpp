#include "distributed/mesh_partition.hpp"  // mesh/mesh.hpp brings the cell faces (quadrature/cell_type.hpp)

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <map>
#include <numeric>
#include <span>
#include <stdexcept>

namespace hofem {

namespace {

// Splits elements [first, last) of `order` (by centroid) into `parts` parts numbered from `first_part`.
void bisect(const Eigen::Matrix3Xd& centroid, std::vector<int>& order, int first, int last, int first_part, int parts,
            std::vector<int>& part) {
  if (parts == 1) {
    for (int i = first; i < last; ++i) part[order[i]] = first_part;
    return;
  }
  Eigen::Vector3d lo = centroid.col(order[first]), hi = lo;
  for (int i = first + 1; i < last; ++i) {
    lo = lo.cwiseMin(centroid.col(order[i]));
    hi = hi.cwiseMax(centroid.col(order[i]));
  }
  int axis = 0;
  (hi - lo).maxCoeff(&axis);
  const int left_parts = parts / 2;
  // Element counts proportional to the parts on each side (rounded down on the left).
  const int mid = first + static_cast<int>(static_cast<long long>(last - first) * left_parts / parts);
  // Ties broken by element id, so the result does not depend on the sort's whims.
  std::nth_element(order.begin() + first, order.begin() + mid, order.begin() + last, [&](int a, int b) {
    const double ca = centroid(axis, a), cb = centroid(axis, b);
    return ca < cb || (ca == cb && a < b);
  });
  bisect(centroid, order, first, mid, first_part, left_parts, part);
  bisect(centroid, order, mid, last, first_part + left_parts, parts - left_parts, part);
}

}  // namespace

std::vector<int> partition_elements(const Mesh& mesh, int parts) {
  const int ne = mesh.num_elements();
  if (parts < 1 || parts > ne)
    throw std::invalid_argument(fmt::format("partition_elements: {} parts for {} elements", parts, ne));
  Eigen::Matrix3Xd centroid = Eigen::Matrix3Xd::Zero(3, ne);
  for (int e = 0; e < ne; ++e) {
    for (int i = 0; i < mesh.vertices_per_element(); ++i) centroid.col(e) += mesh.nodes.col(mesh.elements(i, e));
    centroid.col(e) /= mesh.vertices_per_element();
  }
  std::vector<int> order(ne), part(ne, 0);
  std::iota(order.begin(), order.end(), 0);
  bisect(centroid, order, 0, ne, 0, parts, part);
  return part;
}

std::vector<int> node_owners(const Mesh& mesh, const std::vector<int>& part) {
  if (static_cast<int>(part.size()) != mesh.num_elements())
    throw std::invalid_argument(fmt::format("node_owners: {} parts for {} elements", part.size(), mesh.num_elements()));
  std::vector<int> owner(mesh.num_nodes(), -1);
  for (int e = 0; e < mesh.num_elements(); ++e)
    for (int i = 0; i < mesh.nodes_per_element(); ++i) {
      int& o = owner[mesh.elements(i, e)];
      o = o < 0 ? part[e] : std::min(o, part[e]);
    }
  return owner;
}

PartitionQuality partition_quality(const Mesh& mesh, const std::vector<int>& part, int parts) {
  PartitionQuality q;
  q.parts = parts;
  q.elements.assign(parts, 0);
  q.owned_nodes.assign(parts, 0);
  q.ghost_nodes.assign(parts, 0);
  const std::vector<int> owner = node_owners(mesh, part);
  for (int e = 0; e < mesh.num_elements(); ++e) {
    if (part[e] < 0 || part[e] >= parts)
      throw std::invalid_argument(fmt::format("partition_quality: element {} in part {} of {}", e, part[e], parts));
    ++q.elements[part[e]];
  }
  for (int o : owner)
    if (o >= 0) ++q.owned_nodes[o];
  // Ghosts: per part, the distinct nodes of its elements owned by another part.
  std::vector<int> seen(mesh.num_nodes(), -1);
  std::vector<std::vector<int>> elements_of(parts);
  for (int e = 0; e < mesh.num_elements(); ++e) elements_of[part[e]].push_back(e);
  for (int p = 0; p < parts; ++p)
    for (int e : elements_of[p])
      for (int i = 0; i < mesh.nodes_per_element(); ++i) {
        const int n = mesh.elements(i, e);
        if (seen[n] == p) continue;
        seen[n] = p;
        if (owner[n] != p) ++q.ghost_nodes[p];
      }
  // Faces shared by two elements of different parts.
  std::map<std::array<int, 4>, int> first_part;
  auto count_cut = [&](int e, std::span<const int> face) {
    std::array<int, 4> key{-1, -1, -1, -1};  // a triangle's unused slot stays -1 and sorts first
    for (std::size_t k = 0; k < face.size(); ++k) key[k] = mesh.elements(face[k], e);
    std::sort(key.begin(), key.end());
    auto [it, fresh] = first_part.try_emplace(key, part[e]);
    if (!fresh && it->second != part[e]) ++q.cut_faces;
  };
  for (int e = 0; e < mesh.num_elements(); ++e) {
    if (mesh.cell == CellType::Tetrahedron)
      for (const auto& f : kTetrahedronFaces) count_cut(e, f);
    else
      for (const auto& f : kHexahedronFaces) count_cut(e, f);
  }
  const double mean = static_cast<double>(mesh.num_elements()) / parts;
  q.imbalance = *std::max_element(q.elements.begin(), q.elements.end()) / mean - 1.0;
  for (int p = 0; p < parts; ++p)
    if (q.owned_nodes[p] + q.ghost_nodes[p] > 0)
      q.ghost_fraction =
          std::max(q.ghost_fraction, static_cast<double>(q.ghost_nodes[p]) / (q.owned_nodes[p] + q.ghost_nodes[p]));
  return q;
}

}  // namespace hofem
