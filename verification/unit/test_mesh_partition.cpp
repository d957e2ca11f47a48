// Element partitions and the distributed row numbering (issue 7's groundwork).
#include "assembly/distributed_dofs.hpp"
#include "mesh/box_mesh.hpp"
#include "mesh/mesh_partition.hpp"
#include "mesh/tube_mesh.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <set>

namespace hofem {
namespace {

// Any number of parts: every element in exactly one part, counts within one
// of each other (RCB splits counts proportionally to the parts on each side).
TEST(MeshPartition, BalancedForAnyNumberOfParts) {
  const Mesh mesh = hollow_cylinder_mesh(0.5, 1.0, 2.0, 2, 12, 5, CellType::Tetrahedron, 2);
  for (int parts : {1, 2, 3, 5, 8}) {
    const std::vector<int> part = partition_elements(mesh, parts);
    std::vector<int> count(parts, 0);
    for (int p : part) {
      ASSERT_GE(p, 0);
      ASSERT_LT(p, parts);
      ++count[p];
    }
    const auto [lo, hi] = std::minmax_element(count.begin(), count.end());
    EXPECT_LE(*hi - *lo, 1) << parts;
    const PartitionQuality q = partition_quality(mesh, part, parts);
    EXPECT_EQ(q.elements, count);
    EXPECT_EQ(std::accumulate(q.owned_nodes.begin(), q.owned_nodes.end(), 0), mesh.num_nodes());
    EXPECT_LE(q.imbalance, static_cast<double>(parts) / mesh.num_elements() + 1e-15);
  }
  EXPECT_THROW(partition_elements(mesh, 0), std::invalid_argument);
  EXPECT_THROW(partition_elements(mesh, mesh.num_elements() + 1), std::invalid_argument);
}

// Two parts of an 8 x 4 x 4 box split across its longest axis (x) at x = 1/2:
// the cut is the mid-plane, whose 4 x 4 squares are 16 hex faces or 32 tet
// faces; part 0 owns the plane's 5 x 5 vertices (lowest part), so part 1 has
// them as ghosts (and for Tet10 also the plane's edge midpoints: 9 x 9 nodes).
TEST(MeshPartition, TwoPartsOfABoxCutAtTheMidPlane) {
  struct Case {
    CellType cell;
    int order, cut_faces, ghosts;
  };
  for (const Case c : {Case{CellType::Hexahedron, 1, 16, 25}, Case{CellType::Tetrahedron, 1, 32, 25},
                       Case{CellType::Tetrahedron, 2, 32, 81}}) {
    const Mesh mesh = box_mesh(BoxSpec{{0, 0, 0}, {1, 0.5, 0.5}, {8, 4, 4}}, c.cell, c.order);
    const std::vector<int> part = partition_elements(mesh, 2);
    for (int e = 0; e < mesh.num_elements(); ++e) {
      double x = 0.0;
      for (int i = 0; i < mesh.vertices_per_element(); ++i) x += mesh.nodes(0, mesh.elements(i, e));
      EXPECT_EQ(part[e], x / mesh.vertices_per_element() < 0.5 ? 0 : 1) << e;
    }
    const PartitionQuality q = partition_quality(mesh, part, 2);
    EXPECT_EQ(q.cut_faces, c.cut_faces);
    EXPECT_EQ(q.ghost_nodes, (std::vector<int>{0, c.ghosts}));
  }
}

// One part: the distributed numbering is the serial free numbering, so 1-rank
// and serial runs assemble the same rows in the same order.
TEST(DistributedDofs, OnePartIsTheSerialNumbering) {
  const Mesh mesh = box_mesh(unit_cube(3), CellType::Tetrahedron, 2);
  const DofMap dofs(mesh.num_nodes(), mesh.node_set("xmin"));
  const DistributedDofs d = distribute_dofs(mesh, dofs, std::vector<int>(mesh.num_elements(), 0), 1);
  EXPECT_EQ(d.global_row, dofs.free_index());
  EXPECT_EQ(d.first_row, (std::vector<int>{0, dofs.num_free()}));
  EXPECT_TRUE(d.ghost_rows[0].empty());
}

// K parts: the rows are a permutation of the free DOFs, each part's rows are
// its owned nodes' DOFs and contiguous, constrained DOFs have none, and a
// part's ghost rows are exactly the rows of its elements' DOFs it does not own.
TEST(DistributedDofs, PartsOwnContiguousRowsAndListTheirGhosts) {
  const Mesh mesh = box_mesh(BoxSpec{{0, 0, 0}, {2, 1, 1}, {6, 3, 3}}, CellType::Hexahedron, 2);
  const DofMap dofs(mesh.num_nodes(), mesh.node_set("xmin"));
  const int parts = 3;
  const std::vector<int> part = partition_elements(mesh, parts);
  const DistributedDofs d = distribute_dofs(mesh, dofs, part, parts);
  const std::vector<int> owner = node_owners(mesh, part);
  std::vector<int> rows;
  for (int dof = 0; dof < dofs.num_dofs(); ++dof) {
    const int row = d.global_row[dof];
    if (dofs.free_index(dof) < 0) {
      EXPECT_EQ(row, -1);
      continue;
    }
    const int p = owner[dof / 3];
    EXPECT_GE(row, d.first_row[p]);
    EXPECT_LT(row, d.first_row[p + 1]);
    rows.push_back(row);
  }
  std::sort(rows.begin(), rows.end());
  for (int i = 0; i < static_cast<int>(rows.size()); ++i) ASSERT_EQ(rows[i], i);
  EXPECT_EQ(d.first_row.back(), dofs.num_free());
  for (int p = 0; p < parts; ++p) {
    std::set<int> expected;
    for (int e = 0; e < mesh.num_elements(); ++e)
      if (part[e] == p)
        for (int i = 0; i < mesh.nodes_per_element(); ++i)
          for (int c = 0; c < 3; ++c) {
            const int row = d.global_row[3 * mesh.elements(i, e) + c];
            if (row >= 0 && (row < d.first_row[p] || row >= d.first_row[p + 1])) expected.insert(row);
          }
    EXPECT_EQ(d.ghost_rows[p], std::vector<int>(expected.begin(), expected.end())) << p;
    EXPECT_EQ(d.halo_bytes(p), 8LL * static_cast<long long>(expected.size()));
  }
  EXPECT_GT(d.ghost_rows[1].size(), 0u);
  EXPECT_THROW(distribute_dofs(mesh, dofs, std::vector<int>(3, 0), parts), std::invalid_argument);
  std::vector<int> bad = part;
  bad[0] = parts;
  EXPECT_THROW(distribute_dofs(mesh, dofs, bad, parts), std::invalid_argument);
}

}  // namespace
}  // namespace hofem
