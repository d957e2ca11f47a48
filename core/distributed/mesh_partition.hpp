#pragma once
// Element partitions for distributed assembly: every MPI rank
// assembles only the elements of its part.
//
// Recursive coordinate bisection (RCB) of the element centroids: the longest
// axis of a part's centroid box is split at the element whose rank along it
// gives the two halves element counts proportional to the numbers of parts they
// will be cut into, recursively, so any number of parts K >= 1 comes out with
// counts differing by at most one. RCB is the fallback the issue names next to
// METIS: deterministic, O(n log n log K), no dependency, and on the structured
// and quasi-uniform meshes of this project its cuts are planes, which is close to
// what a graph partitioner finds. (METIS minimises the edge cut on irregular
// meshes; the quality report below is what would show the difference.)
#include "mesh/mesh.hpp"

#include <vector>

namespace hofem {

/// part[e] in [0, parts) for every element. Throws std::invalid_argument for
/// parts < 1 or parts > num_elements.
std::vector<int> partition_elements(const Mesh& mesh, int parts);

/// How good a partition is for distributed assembly. A node is owned by the
/// lowest part among its elements; a part's ghosts are the nodes its elements
/// touch but another part owns (the halo each rank receives).
struct PartitionQuality {
  int parts = 0;
  std::vector<int> elements;     ///< per part
  std::vector<int> owned_nodes;  ///< per part
  std::vector<int> ghost_nodes;  ///< per part
  int cut_faces = 0;             ///< element faces shared by elements of different parts (dual-graph edge cut)
  double imbalance = 0.0;        ///< max elements per part / mean - 1
  double ghost_fraction = 0.0;   ///< max over parts of ghosts / (owned + ghosts)
};
PartitionQuality partition_quality(const Mesh& mesh, const std::vector<int>& part, int parts);

/// Owner part of every node (the lowest part among its elements; -1 for a node in no element).
std::vector<int> node_owners(const Mesh& mesh, const std::vector<int>& part);

}  // namespace hofem
