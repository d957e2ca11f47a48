#include "assembly/distributed_dofs.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace hofem {

DistributedDofs distribute_dofs(const DistributedMesh& dm, const DofMap& dofs) {
  const LocalMesh& local = dm.local;
  if (dofs.num_dofs() != 3 * local.mesh.num_nodes())
    throw std::invalid_argument(fmt::format("distribute_dofs: a DOF map of {} DOFs for a piece of {} nodes",
                                            dofs.num_dofs(), local.mesh.num_nodes()));
  const int n = dofs.num_free();
  std::vector<std::int64_t> ids(n);
  std::vector<int> owner(n);
  int owned = 0;
  for (int i = 0; i < n; ++i) {
    const int dof = dofs.free_dofs()[i], node = dof / 3;
    ids[i] = 3 * local.global_node[node] + dof % 3;
    owner[i] = local.owner[node];
    owned += owner[i] == dm.rank;
  }
  DistributedDofs d{0, owned, 0, {}, Halo(dm.comm, ids, owner, 1)};
  long long mine = owned, before = 0, total = 0;
  MPI_Exscan(&mine, &before, 1, MPI_LONG_LONG, MPI_SUM, dm.comm);
  if (dm.rank == 0) before = 0;  // MPI_Exscan leaves rank 0's result undefined
  MPI_Allreduce(&mine, &total, 1, MPI_LONG_LONG, MPI_SUM, dm.comm);
  d.first_row = before;
  d.global_rows = total;
  // Owned rows in local (= global node) order; ghosts receive theirs from the
  // owner (a double holds any row below 2^53 exactly).
  Eigen::VectorXd rows = Eigen::VectorXd::Constant(n, -1.0);
  std::int64_t next = d.first_row;
  for (int i = 0; i < n; ++i)
    if (d.free.owned(i)) rows[i] = static_cast<double>(next++);
  d.free.update_ghosts(rows);
  d.row.resize(n);
  for (int i = 0; i < n; ++i) d.row[i] = static_cast<std::int64_t>(rows[i]);
  return d;
}

}  // namespace hofem
