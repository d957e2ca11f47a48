#pragma once
// One rank's piece of a partitioned mesh: the elements of its part and
// the nodes they touch, renumbered locally, with each node's global id and
// owner. A distributed run builds its DOF map, sparsity pattern, element data
// and vectors on this piece only, so that per-rank memory falls as N / ranks
// (plus the halo), instead of holding the whole mesh's pattern on every rank.
//
// Local nodes keep the global order (ascending global id), so with one part the
// local mesh is the global mesh, node for node and element for element, and
// everything numbered from it (DOFs, rows) is the serial numbering.
// Node ownership (mesh_partition.hpp's node_owners): the lowest part among a
// node's elements. Owned nodes are the rank's rows of the distributed system;
// the others (ghosts) are rows another rank owns.
#include "mesh/mesh.hpp"

#include <cstdint>
#include <vector>

namespace hofem {

struct LocalMesh {
  int part = 0;
  Mesh mesh;                        ///< the part's elements over its local nodes; node and element sets restricted
  std::vector<std::int64_t> global_node;  ///< per local node: its global id (ascending)
  std::vector<int> global_element;  ///< per local element: its global index (ascending)
  std::vector<int> owner;           ///< per local node: the part that owns it
  /// Size of the id spaces: every global node id is < global_nodes. For a piece of a
  /// given mesh that is its node count; box_piece() numbers nodes by lattice index,
  /// whose space has gaps for Hex20 (face and cube centres are not nodes), and
  /// gather_nodal() then returns the lattice's layout, not box_mesh()'s numbering.
  std::int64_t global_nodes = 0;
  int global_elements = 0;

  bool owns(int local_node) const { return owner[local_node] == part; }
  int owned_nodes() const;
};

/// Part p of `global` under the element partition `part` (part[e] in [0, parts)).
/// Throws std::invalid_argument if `part` does not fit the mesh or p has no elements.
LocalMesh extract_part(const Mesh& global, const std::vector<int>& part, int p);

/// The local indices (ascending) of those of `global_nodes` present in the piece.
std::vector<int> to_local_nodes(const LocalMesh& local, const std::vector<int>& global_nodes);

/// Per-element data of the global mesh restricted to the piece's elements.
template <class T>
std::vector<T> restrict_to_elements(const LocalMesh& local, const std::vector<T>& per_global_element) {
  if (per_global_element.empty()) return {};
  std::vector<T> out;
  out.reserve(local.global_element.size());
  for (int e : local.global_element) out.push_back(per_global_element[e]);
  return out;
}

}  // namespace hofem
