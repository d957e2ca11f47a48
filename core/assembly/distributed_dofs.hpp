#pragma once
// A mesh distributed over MPI ranks, and the global numbering of its free DOFs.
//
// DistributedMesh: each rank keeps only its piece (mesh/local_mesh.hpp: the
// elements of its part, recursive coordinate bisection, and the nodes they
// touch, owned or ghost) and the node halo that turns partial nodal sums into
// full ones. Assembly, the DOF map, the sparsity pattern and every vector then
// live on the piece: per-rank memory scales with N / ranks plus the halo.
//
// DistributedDofs: hypre's IJ matrices give each rank a contiguous range of
// global rows, so the free DOFs of owned nodes are numbered rank by rank, in
// global node order within a rank; ghosts learn their rows from their owners.
// With one rank this is exactly the serial DofMap's free numbering, so serial
// and distributed runs assemble the same matrix in the same row order.
#include "assembly/dof_map.hpp"
#include "mesh/local_mesh.hpp"
#include "mesh/mesh.hpp"
#include "parallel/halo.hpp"

#include <mpi.h>

#include <cstdint>
#include <vector>

namespace hofem {

struct DistributedMesh {
  MPI_Comm comm = MPI_COMM_WORLD;
  int rank = 0, ranks = 1;
  LocalMesh local;
  Halo nodes;  ///< over the local nodes, 3 values per node (vectors over all local DOFs)

  const Mesh& mesh() const { return local.mesh; }
  /// Sum over ranks of per-rank values (energies of each rank's elements).
  double sum(double value) const;
  /// Collective. A nodal field of the piece (3 values per local node,
  /// consistent) gathered to `root` in global node order (3 per global node);
  /// empty on the other ranks. For output: one VTU, one stats file.
  Eigen::VectorXd gather_nodal(const Eigen::VectorXd& local, int root = 0) const;
  /// Collective. Per-element values of the piece gathered to `root` in global element order.
  Eigen::VectorXd gather_elemental(const Eigen::VectorXd& local, int root = 0) const;
};

/// Collective: partitions `global` over the ranks of comm (partition_elements)
/// and keeps this rank's piece. Every rank passes the same global mesh.
DistributedMesh distribute_mesh(MPI_Comm comm, const Mesh& global);
/// Collective: a piece each rank made itself (e.g. box_piece: no rank holds the
/// whole mesh); its part must be the rank.
DistributedMesh distribute_piece(MPI_Comm comm, LocalMesh piece);

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
