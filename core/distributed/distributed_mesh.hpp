#pragma once
// A mesh distributed over MPI ranks: each rank keeps only its piece
// (distributed/local_mesh.hpp: the elements of its part, recursive coordinate
// bisection, and the nodes they touch, owned or ghost) and the node halo that
// turns partial nodal sums into full ones. Assembly, the DOF map, the sparsity
// pattern and every vector then live on the piece: per-rank memory scales with
// N / ranks plus the halo. MPI_Comm comes from parallel/, the one layer that
// includes <mpi.h>.
#include "distributed/local_mesh.hpp"
#include "mesh/mesh.hpp"
#include "parallel/collectives.hpp"
#include "parallel/halo.hpp"

#include <Eigen/Core>

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

}  // namespace hofem
