#pragma once
// The global numbering of the free DOFs of a mesh distributed over MPI ranks
// (distributed/distributed_mesh.hpp).
//
// DistributedDofs: hypre's IJ matrices give each rank a contiguous range of
// global rows, so the free DOFs of owned nodes are numbered rank by rank, in
// global node order within a rank; ghosts learn their rows from their owners.
// With one rank this is exactly the serial DofMap's free numbering, so serial
// and distributed runs assemble the same matrix in the same row order.
#include "assembly/dof_map.hpp"
#include "distributed/distributed_mesh.hpp"
#include "parallel/halo.hpp"

#include <cstdint>
#include <vector>

namespace hofem {

struct DistributedDofs {
  std::int64_t first_row = 0;    ///< this rank owns rows [first_row, first_row + owned_rows)
  int owned_rows = 0;
  std::int64_t global_rows = 0;  ///< free DOFs over all ranks
  std::vector<std::int64_t> row; ///< per local free DOF: its global row
  Halo free;                     ///< over the local free DOFs (vectors of Newton and the solver)
};

/// Collective. `dofs` is the DofMap of the local mesh; a node is constrained on
/// every rank that has it or on none (constraints come from global node sets).
DistributedDofs distribute_dofs(const DistributedMesh& mesh, const DofMap& dofs);

}  // namespace hofem
