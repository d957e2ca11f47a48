#pragma once
// The row numbering distributed assembly needs (issue 7): hypre's IJ matrices
// give each rank a contiguous range of global rows, so the free DOFs are
// renumbered part by part: rank r owns rows [first_row[r], first_row[r+1]),
// the DOFs of the nodes it owns (node_owners: the lowest part among a node's
// elements), in node order, three per node. With one part this is exactly the
// serial DofMap's free numbering, so serial and distributed runs assemble the
// same matrix in the same row order.
//
// A rank assembles its own elements; their contributions to rows owned by
// another rank (its ghost rows) are what crosses the network during assembly,
// and the ghost rows' values are what each matrix-vector product receives.
#include "assembly/dof_map.hpp"
#include "basis/element_rules.hpp"
#include "mesh/mesh.hpp"

#include <vector>

namespace hofem {

struct DistributedDofs {
  int parts = 1;
  std::vector<int> first_row;                ///< parts + 1 entries; first_row[parts] = number of free DOFs
  std::vector<int> global_row;               ///< per DOF (3 * num_nodes): its global row, -1 if constrained
  std::vector<std::vector<int>> ghost_rows;  ///< per part: rows its elements touch that another part owns (ascending)
  int owned_rows(int p) const { return first_row[p + 1] - first_row[p]; }
  /// Bytes a part receives per halo exchange of one double per ghost row (a
  /// matrix-vector product's communication volume).
  long long halo_bytes(int p) const { return 8LL * static_cast<long long>(ghost_rows[p].size()); }
};

/// Throws std::invalid_argument if `part` does not match the mesh or names a part outside [0, parts).
DistributedDofs distribute_dofs(const Mesh& mesh, const DofMap& dofs, const std::vector<int>& part, int parts);

/// Rules that make an Assembler integrate only the elements of part p (the
/// others get empty rules: they contribute nothing), so the ordinary serial
/// assembly produces one rank's share of a distributed system. `base` (e.g.
/// finite-cell rules) is kept for the elements of p.
/// mass_too = false keeps every element's mass rule (replicated mass, as the
/// distributed dynamics uses it).
ElementRules rules_of_part(const Mesh& mesh, const std::vector<int>& part, int p, const ElementRules& base = {},
                           bool mass_too = true);

}  // namespace hofem
