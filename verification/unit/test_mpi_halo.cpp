// The distributed mesh, its halo and the global row numbering, run by
// ctest on one rank (hofem_mpi_tests), two (mpi.two_ranks) and three
// (mpi.three_ranks). Expected values come from the global mesh and the element
// partition, computed independently of the code under test.
#include "assembly/distributed_dofs.hpp"
#include "mesh/box_mesh.hpp"
#include "distributed/mesh_partition.hpp"
#include "parallel/mpi_runtime.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <set>

namespace hofem {
namespace {

int world_size() {
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return size;
}

// The piece holds exactly this rank's elements and the nodes they touch; the
// halo's sum of ones gives each node the number of ranks whose elements touch
// it (counted here from the global partition), and update_ghosts copies the
// owner's value. Exact: small integers.
TEST(DistributedHalo, SumAndUpdateMatchTheGlobalPartition) {
  ensure_hypre();
  const Mesh mesh = box_mesh(BoxSpec{{0, 0, 0}, {3, 1, 1}, {6, 2, 2}}, CellType::Hexahedron, 2);
  const DistributedMesh piece = distribute_mesh(MPI_COMM_WORLD, mesh);
  const std::vector<int> part = partition_elements(mesh, piece.ranks);
  std::vector<std::set<int>> touching(mesh.num_nodes());
  int mine = 0;
  for (int e = 0; e < mesh.num_elements(); ++e) {
    mine += part[e] == piece.rank;
    for (int i = 0; i < mesh.nodes_per_element(); ++i) touching[mesh.elements(i, e)].insert(part[e]);
  }
  const LocalMesh& local = piece.local;
  ASSERT_EQ(local.mesh.num_elements(), mine);
  ASSERT_TRUE(std::is_sorted(local.global_node.begin(), local.global_node.end()));
  for (int k = 0; k < local.mesh.num_elements(); ++k)  // same element, same nodes, same coordinates
    for (int i = 0; i < mesh.nodes_per_element(); ++i) {
      const int n = local.mesh.elements(i, k);
      ASSERT_EQ(local.global_node[n], mesh.elements(i, local.global_element[k]));
      ASSERT_EQ(local.mesh.nodes.col(n), mesh.nodes.col(local.global_node[n]));
    }
  Eigen::VectorXd ones = Eigen::VectorXd::Ones(3 * local.mesh.num_nodes());
  piece.nodes.sum(ones);
  Eigen::VectorXd ids(3 * local.mesh.num_nodes());
  int ghosts = 0;
  for (int n = 0; n < local.mesh.num_nodes(); ++n) {
    const auto& ranks = touching[local.global_node[n]];
    EXPECT_EQ(local.owner[n], *ranks.begin());  // the lowest part among its elements
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(ones[3 * n + c], static_cast<double>(ranks.size()));
      ids[3 * n + c] = local.owns(n) ? static_cast<double>(local.global_node[n]) : -1.0;
    }
    ghosts += !local.owns(n);
  }
  piece.nodes.update_ghosts(ids);
  for (int n = 0; n < local.mesh.num_nodes(); ++n) EXPECT_EQ(ids[3 * n], static_cast<double>(local.global_node[n]));
  EXPECT_EQ(piece.nodes.ghosts(), ghosts);
  EXPECT_EQ(piece.nodes.bytes_per_update(), 24LL * ghosts);
  if (piece.ranks == 1) {
    EXPECT_EQ(ghosts, 0);
  } else {
    EXPECT_GT(piece.nodes.neighbours(), 0);
  }
  // dot() counts every node once: the sum of global ids over all nodes.
  Eigen::VectorXd x_only = Eigen::VectorXd::Zero(ids.size());
  for (int n = 0; n < local.mesh.num_nodes(); ++n) x_only[3 * n] = 1.0;
  const double expected = 0.5 * static_cast<double>(mesh.num_nodes()) * (mesh.num_nodes() - 1);
  EXPECT_EQ(piece.nodes.dot(ids, x_only), expected);
  // Gathered fields arrive in global order on rank 0.
  const Eigen::VectorXd gathered = piece.gather_nodal(ids);
  if (piece.rank == 0) {
    for (int n = 0; n < mesh.num_nodes(); ++n) EXPECT_EQ(gathered[3 * n + 2], n);
  }
  Eigen::VectorXd element_ids(local.mesh.num_elements());
  for (int k = 0; k < local.mesh.num_elements(); ++k) element_ids[k] = local.global_element[k];
  const Eigen::VectorXd elements = piece.gather_elemental(element_ids);
  if (piece.rank == 0) {
    for (int e = 0; e < mesh.num_elements(); ++e) EXPECT_EQ(elements[e], e);
  }
}

// Rows: contiguous per rank, in rank order, owned nodes' DOFs in global node
// order within a rank (so one rank gives the serial free numbering), and every
// ghost DOF carries its owner's row. The expected rows are counted here from
// the global mesh, the partition and the constrained set.
TEST(DistributedHalo, GlobalRowsFollowOwnersAndGlobalNodeOrder) {
  ensure_hypre();
  const Mesh mesh = box_mesh(BoxSpec{{0, 0, 0}, {2, 1, 1}, {6, 3, 3}}, CellType::Tetrahedron, 2);
  const DistributedMesh piece = distribute_mesh(MPI_COMM_WORLD, mesh);
  const DofMap serial(mesh.num_nodes(), mesh.node_set("xmin"));
  const std::vector<int> owner = node_owners(mesh, partition_elements(mesh, piece.ranks));
  std::vector<long long> expected(serial.num_dofs(), -1);
  long long next = 0;
  for (int p = 0; p < piece.ranks; ++p)
    for (int dof = 0; dof < serial.num_dofs(); ++dof)
      if (owner[dof / 3] == p && serial.free_index(dof) >= 0) expected[dof] = next++;
  const DofMap dofs(piece.mesh().num_nodes(), piece.mesh().node_set("xmin"));
  const DistributedDofs rows = distribute_dofs(piece, dofs);
  EXPECT_EQ(rows.global_rows, serial.num_free());
  for (int i = 0; i < dofs.num_free(); ++i) {
    const int dof = dofs.free_dofs()[i];
    const long long global_dof = 3 * piece.local.global_node[dof / 3] + dof % 3;
    EXPECT_EQ(rows.row[i], expected[global_dof]) << "rank " << piece.rank << " DOF " << global_dof;
    if (rows.free.owned(i)) {
      EXPECT_GE(rows.row[i], rows.first_row);
      EXPECT_LT(rows.row[i], rows.first_row + rows.owned_rows);
    }
  }
  if (piece.ranks == 1) {
    for (int i = 0; i < dofs.num_free(); ++i) EXPECT_EQ(rows.row[i], i);  // the serial numbering
  }
  // A DOF map in which the owner constrains a shared node that a neighbour
  // leaves free is refused on every rank (the neighbour asks for a row the
  // owner does not have).
  if (piece.ranks > 1) {
    Eigen::VectorXd touching = Eigen::VectorXd::Ones(3 * piece.mesh().num_nodes());
    piece.nodes.sum(touching);
    std::vector<int> constrained = piece.mesh().node_set("xmin");
    if (piece.rank == 0)
      for (int n = 0; n < piece.mesh().num_nodes(); ++n)
        if (piece.local.owns(n) && touching[3 * n] > 1.0) {
          constrained.push_back(n);
          break;
        }
    EXPECT_THROW(distribute_dofs(piece, DofMap(piece.mesh().num_nodes(), constrained)), std::logic_error);
  }
}

// Bad input: a halo whose sizes disagree, or whose owner is not a rank.
TEST(DistributedHalo, RefusesMalformedInput) {
  ensure_hypre();
  EXPECT_THROW(Halo(MPI_COMM_WORLD, {1, 2}, {0}, 1), std::invalid_argument);
  EXPECT_THROW(Halo(MPI_COMM_WORLD, {1}, {world_size()}, 1), std::invalid_argument);
  const Halo halo(MPI_COMM_WORLD, {}, {}, 3);
  Eigen::VectorXd wrong(2);
  EXPECT_THROW(halo.sum(wrong), std::invalid_argument);
}

}  // namespace
}  // namespace hofem
