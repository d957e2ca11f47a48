#include "mesh/mesh_upgrade.hpp"

#include "basis/lagrange_nodes.hpp"
#include "quadrature/cell_type.hpp"
#include "basis/element_orders.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <unordered_map>

namespace hofem {

namespace {

// Key of a lattice point: up to four (vertex id, barycentric lattice weight)
// pairs, sorted by vertex id, unused slots -1.
using Key = std::array<int, 8>;

struct KeyHash {
  size_t operator()(const Key& k) const {
    size_t h = 1469598103934665603ull;
    for (int v : k) h = (h ^ static_cast<size_t>(v + 1)) * 1099511628211ull;
    return h;
  }
};

Key make_key(std::vector<std::pair<int, int>> pairs) {
  std::sort(pairs.begin(), pairs.end());
  Key k;
  k.fill(-1);
  for (size_t i = 0; i < pairs.size(); ++i) {
    k[2 * i] = pairs[i].first;
    k[2 * i + 1] = pairs[i].second;
  }
  return k;
}

std::vector<int> key_vertices(const Key& k) {
  std::vector<int> v;
  for (int i = 0; i < 4 && k[2 * i] >= 0; ++i) v.push_back(k[2 * i]);
  return v;
}

// Boundary faces of the linear mesh (faces used by exactly one element), as
// sorted vertex lists: triangles for tets, quads for hexes.
std::set<std::vector<int>> boundary_faces(const Mesh& m) {
  std::map<std::vector<int>, int> count;
  const bool tet = m.cell == CellType::Tetrahedron;
  for (int e = 0; e < m.num_elements(); ++e)
    for (int f = 0; f < (tet ? 4 : 6); ++f) {
      std::vector<int> face;
      for (int i = 0; i < (tet ? 3 : 4); ++i)
        face.push_back(m.elements(tet ? kTetrahedronFaces[f][i] : kHexahedronFaces[f][i], e));
      std::sort(face.begin(), face.end());
      ++count[face];
    }
  std::set<std::vector<int>> out;
  for (const auto& [face, c] : count)
    if (c == 1) out.insert(face);
  return out;
}

// Node-set membership of new nodes, see the header.
void extend_node_sets(const Mesh& linear, Mesh& out, const std::vector<Key>& keys) {
  const auto faces = boundary_faces(linear);
  // Boundary faces by vertex, to find the faces containing a key's vertices.
  std::unordered_map<int, std::vector<const std::vector<int>*>> faces_of_vertex;
  std::set<int> boundary_vertices;
  for (const auto& f : faces)
    for (int v : f) faces_of_vertex[v].push_back(&f), boundary_vertices.insert(v);
  // Whether a key's vertices lie together on one boundary face.
  auto on_boundary_face = [&](const std::vector<int>& verts) {
    for (const auto* f : faces_of_vertex[verts[0]]) {
      bool contains = true;
      for (int v : verts) contains = contains && std::binary_search(f->begin(), f->end(), v);
      if (contains) return true;
    }
    return false;
  };
  const int nv = linear.num_nodes();
  out.node_sets.clear();
  for (const auto& [name, nodes] : linear.node_sets) {
    if (name == "boundary") continue;
    std::vector<int> members;
    if (const auto es = linear.element_sets.find(name); es != linear.element_sets.end()) {
      // A volume group: every node of its elements.
      for (int e : es->second)
        for (int i = 0; i < out.nodes_per_element(); ++i) members.push_back(out.elements(i, e));
    } else {
      // A surface, curve or point group: new nodes whose key vertices are all in
      // the group and lie together on a boundary face.
      std::vector<char> in(nv, 0);
      for (int v : nodes) in[v] = 1;
      members.assign(nodes.begin(), nodes.end());
      for (size_t n = 0; n < keys.size(); ++n) {
        const auto verts = key_vertices(keys[n]);
        if (verts.size() < 2) continue;  // vertices keep their own membership
        bool all = true;
        for (int v : verts) all = all && in[v];
        if (all && on_boundary_face(verts)) members.push_back(static_cast<int>(n));
      }
    }
    std::sort(members.begin(), members.end());
    members.erase(std::unique(members.begin(), members.end()), members.end());
    out.node_sets[name] = std::move(members);
  }
  std::vector<int> boundary(boundary_vertices.begin(), boundary_vertices.end());
  for (size_t n = 0; n < keys.size(); ++n) {
    const auto verts = key_vertices(keys[n]);
    if (verts.size() >= 2 && on_boundary_face(verts)) boundary.push_back(static_cast<int>(n));
  }
  std::sort(boundary.begin(), boundary.end());
  out.node_sets["boundary"] = std::move(boundary);
}

}  // namespace

Mesh upgrade_order(const Mesh& linear, int order) {
  if (linear.order != 1) throw MeshError(fmt::format("upgrade_order: input mesh must be linear, it has order {}", linear.order));
  const int npe = nodes_per_element(linear.cell, order);
  Mesh out;
  out.cell = linear.cell;
  out.order = order;
  out.element_sets = linear.element_sets;
  out.source = linear.source;
  out.elements.resize(npe, linear.num_elements());

  // Local node -> (local vertex, lattice weight) pairs.
  std::vector<std::vector<std::pair<int, int>>> local;
  int denom = order;
  if (linear.cell == CellType::Tetrahedron) {
    for (const auto& l : tetrahedron_lattice(order)) {
      const int w[4] = {order - l[0] - l[1] - l[2], l[0], l[1], l[2]};
      std::vector<std::pair<int, int>> p;
      for (int a = 0; a < 4; ++a)
        if (w[a] > 0) p.push_back({a, w[a]});
      local.push_back(p);
    }
  } else {
    // From Hex8, the only higher order hexahedra support is Hex20.
    if (!supports_order(CellType::Hexahedron, order))
      throw MeshError(fmt::format("upgrade_order: hexahedra support {}, got {}", supported_orders(CellType::Hexahedron), order));
    denom = 2;
    for (int v = 0; v < 8; ++v) local.push_back({{v, 2}});
    const int edges[12][2] = {{0, 1}, {0, 3}, {0, 4}, {1, 2}, {1, 5}, {2, 3}, {2, 6}, {3, 7}, {4, 5}, {4, 7}, {5, 6}, {6, 7}};
    for (const auto& e : edges) local.push_back({{e[0], 1}, {e[1], 1}});
  }

  const int nv = linear.num_nodes();
  std::vector<Key> keys;
  keys.reserve(static_cast<size_t>(nv) + static_cast<size_t>(linear.num_elements()) * npe);
  std::unordered_map<Key, int, KeyHash> id_of;
  for (int v = 0; v < nv; ++v) {
    keys.push_back(make_key({{v, denom}}));
    id_of.emplace(keys.back(), v);
  }
  std::vector<Eigen::Vector3d> coords(linear.nodes.colwise().begin(), linear.nodes.colwise().end());
  for (int e = 0; e < linear.num_elements(); ++e)
    for (int n = 0; n < npe; ++n) {
      std::vector<std::pair<int, int>> pairs;
      for (const auto& [a, w] : local[n]) pairs.push_back({linear.elements(a, e), w});
      const Key k = make_key(pairs);
      auto [it, inserted] = id_of.emplace(k, static_cast<int>(keys.size()));
      if (inserted) {
        keys.push_back(k);
        Eigen::Vector3d x = Eigen::Vector3d::Zero();
        for (const auto& [g, w] : pairs) x += (static_cast<double>(w) / denom) * linear.nodes.col(g);
        coords.push_back(x);
      }
      out.elements(n, e) = it->second;
    }
  out.nodes.resize(3, static_cast<Eigen::Index>(coords.size()));
  for (size_t i = 0; i < coords.size(); ++i) out.nodes.col(static_cast<Eigen::Index>(i)) = coords[i];
  extend_node_sets(linear, out, keys);
  return out;
}

}  // namespace hofem
