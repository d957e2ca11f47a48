#include "distributed/distributed_mesh.hpp"

#include "distributed/mesh_partition.hpp"
#include "parallel/collectives.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace hofem {

double DistributedMesh::sum(double value) const { return sum_over_ranks(value, comm); }

namespace {

// Gathers (id, block values) pairs to root and scatters them into a vector of
// `total` blocks there.
Eigen::VectorXd gather_blocks(MPI_Comm comm, int root, const std::vector<std::int64_t>& ids,
                              const std::vector<double>& values, int block, std::int64_t total) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  const int count = static_cast<int>(ids.size());
  std::vector<int> counts(ranks), displs(ranks + 1, 0);
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, root, comm);
  for (int q = 0; q < ranks; ++q) displs[q + 1] = displs[q] + counts[q];
  std::vector<std::int64_t> all_ids(rank == root ? displs[ranks] : 0);
  MPI_Gatherv(ids.data(), count, MPI_INT64_T, all_ids.data(), counts.data(), displs.data(), MPI_INT64_T, root, comm);
  std::vector<int> vcounts(ranks), vdispls(ranks);
  for (int q = 0; q < ranks; ++q) {
    vcounts[q] = counts[q] * block;
    vdispls[q] = displs[q] * block;
  }
  std::vector<double> all_values(rank == root ? static_cast<size_t>(displs[ranks]) * block : 0);
  MPI_Gatherv(values.data(), count * block, MPI_DOUBLE, all_values.data(), vcounts.data(), vdispls.data(), MPI_DOUBLE,
              root, comm);
  if (rank != root) return {};
  Eigen::VectorXd out = Eigen::VectorXd::Zero(total * block);
  for (size_t k = 0; k < all_ids.size(); ++k)
    for (int c = 0; c < block; ++c) out[all_ids[k] * block + c] = all_values[k * block + c];
  return out;
}

}  // namespace

Eigen::VectorXd DistributedMesh::gather_nodal(const Eigen::VectorXd& v, int root) const {
  if (v.size() != 3 * local.mesh.num_nodes())
    throw std::invalid_argument(fmt::format("gather_nodal: {} values for {} nodes", v.size(), local.mesh.num_nodes()));
  std::vector<std::int64_t> ids;
  std::vector<double> values;
  for (int n = 0; n < local.mesh.num_nodes(); ++n)
    if (local.owns(n)) {  // each node once, from its owner
      ids.push_back(local.global_node[n]);
      for (int c = 0; c < 3; ++c) values.push_back(v[3 * n + c]);
    }
  return gather_blocks(comm, root, ids, values, 3, local.global_nodes);
}

Eigen::VectorXd DistributedMesh::gather_elemental(const Eigen::VectorXd& v, int root) const {
  if (v.size() != local.mesh.num_elements())
    throw std::invalid_argument(fmt::format("gather_elemental: {} values for {} elements", v.size(), local.mesh.num_elements()));
  const std::vector<std::int64_t> ids(local.global_element.begin(), local.global_element.end());
  return gather_blocks(comm, root, ids, std::vector<double>(v.data(), v.data() + v.size()), 1, local.global_elements);
}

DistributedMesh distribute_mesh(MPI_Comm comm, const Mesh& global) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  // RCB is deterministic, so every rank computes the same partition without
  // communication; a run that reads a pre-partitioned mesh would start here.
  return distribute_piece(comm, extract_part(global, partition_elements(global, ranks), rank));
}

DistributedMesh distribute_piece(MPI_Comm comm, LocalMesh piece) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  if (piece.part != rank)
    throw std::invalid_argument(fmt::format("distribute_piece: rank {} was given part {}", rank, piece.part));
  Halo halo(comm, piece.global_node, piece.owner, 3);  // 3 values per node
  return DistributedMesh{comm, rank, ranks, std::move(piece), std::move(halo)};
}

}  // namespace hofem
