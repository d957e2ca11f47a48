// Element partitions and the distributed row numbering.
#include "distributed/local_mesh.hpp"
#include "mesh/box_mesh.hpp"
#include "distributed/mesh_partition.hpp"
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

// One part: the piece is the mesh itself, node for node and element for
// element, so a one-rank run numbers everything as the serial run does.
TEST(LocalMesh, OnePartIsTheWholeMesh) {
  const Mesh mesh = box_mesh(unit_cube(3), CellType::Tetrahedron, 2);
  const LocalMesh local = extract_part(mesh, std::vector<int>(mesh.num_elements(), 0), 0);
  EXPECT_EQ(local.mesh.nodes, mesh.nodes);
  EXPECT_EQ(local.mesh.elements, mesh.elements);
  EXPECT_EQ(local.mesh.node_sets, mesh.node_sets);
  EXPECT_EQ(local.owned_nodes(), mesh.num_nodes());
}

// K parts: each piece has its part's elements over the nodes they touch; every
// node is owned by exactly one piece (the lowest part among its elements), and
// each piece's ghosts are what partition_quality counts; node sets keep the
// nodes the piece has. Bad input is refused.
TEST(LocalMesh, PiecesCoverTheMeshOnce) {
  const Mesh mesh = box_mesh(BoxSpec{{0, 0, 0}, {2, 1, 1}, {6, 3, 3}}, CellType::Hexahedron, 2);
  const int parts = 3;
  const std::vector<int> part = partition_elements(mesh, parts);
  const PartitionQuality q = partition_quality(mesh, part, parts);
  std::vector<int> owned_by(mesh.num_nodes(), 0);
  int elements = 0;
  for (int p = 0; p < parts; ++p) {
    const LocalMesh local = extract_part(mesh, part, p);
    elements += local.mesh.num_elements();
    EXPECT_EQ(local.mesh.num_elements(), q.elements[p]);
    EXPECT_EQ(local.owned_nodes(), q.owned_nodes[p]);
    EXPECT_EQ(local.mesh.num_nodes() - local.owned_nodes(), q.ghost_nodes[p]);
    for (int n = 0; n < local.mesh.num_nodes(); ++n) {
      if (local.owns(n)) ++owned_by[local.global_node[n]];
      EXPECT_EQ(local.mesh.nodes.col(n), mesh.nodes.col(local.global_node[n]));
    }
    for (int n : local.mesh.node_set("xmin")) EXPECT_EQ(mesh.nodes(0, local.global_node[n]), 0.0);
    const std::vector<int> mapped = to_local_nodes(local, mesh.node_set("xmin"));
    EXPECT_EQ(mapped, local.mesh.node_set("xmin"));
  }
  EXPECT_EQ(elements, mesh.num_elements());
  for (int n = 0; n < mesh.num_nodes(); ++n) ASSERT_EQ(owned_by[n], 1) << "node " << n;
  EXPECT_THROW(extract_part(mesh, std::vector<int>(3, 0), 0), std::invalid_argument);
  EXPECT_THROW(extract_part(mesh, part, parts), std::invalid_argument);  // a part without elements
}

}  // namespace
}  // namespace hofem
