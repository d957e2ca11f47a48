// Pieces of a box mesh generated per part (no rank builds the whole
// mesh). Checked against the whole mesh from box_mesh(): every element once,
// with the same nodes in the same order, every node owned once by the lowest
// part that has it, and the box's node sets.
#include "distributed/box_partition.hpp"

#include <gtest/gtest.h>

#include <map>
#include <set>

namespace hofem {
namespace {

struct PieceCase {
  CellType cell;
  int order;
};

class BoxPieces : public ::testing::TestWithParam<PieceCase> {};

TEST_P(BoxPieces, MatchTheWholeMesh) {
  const auto [cell, order] = GetParam();
  const BoxSpec box{{0.0, -1.0, 2.0}, {2.0, 0.5, 3.0}, {4, 3, 2}};
  const Mesh whole = box_mesh(box, cell, order);
  for (int parts : {1, 2, 3, 5}) {
    std::vector<int> element_seen(whole.num_elements(), 0);
    std::map<long long, std::set<int>> holders;  // global node id -> parts that have it
    std::map<long long, int> owner_of;
    std::map<long long, Eigen::Vector3d> position_of;
    int boundary_owned = 0;
    for (int p = 0; p < parts; ++p) {
      const LocalMesh piece = box_piece(box, cell, order, parts, p);
      ASSERT_EQ(piece.mesh.nodes_per_element(), whole.nodes_per_element());
      ASSERT_TRUE(std::is_sorted(piece.global_node.begin(), piece.global_node.end()));
      for (int k = 0; k < piece.mesh.num_elements(); ++k) {
        const int e = piece.global_element[k];
        ++element_seen[e];
        // Same element: the same node positions in the same (Gmsh) order. The
        // two are computed by different formulas, so to rounding (1e-15 of 3).
        for (int i = 0; i < whole.nodes_per_element(); ++i)
          ASSERT_LE((piece.mesh.nodes.col(piece.mesh.elements(i, k)) - whole.nodes.col(whole.elements(i, e))).norm(),
                    1e-14)
              << "parts " << parts << " part " << p << " element " << e << " node " << i;
      }
      for (int n = 0; n < piece.mesh.num_nodes(); ++n) {
        const long long id = piece.global_node[n];
        holders[id].insert(p);
        if (piece.owns(n)) {
          EXPECT_EQ(owner_of.count(id), 0u) << "node " << id << " owned twice";
          owner_of[id] = p;
        }
        if (position_of.count(id)) {
          EXPECT_EQ(position_of[id], piece.mesh.nodes.col(n)) << "shared node differs";  // bitwise
        }
        position_of[id] = piece.mesh.nodes.col(n);
      }
      for (int n : piece.mesh.node_set("boundary")) boundary_owned += piece.owns(n);
      // The box's faces, not the block's: every xmin node is at x = 0.
      for (int n : piece.mesh.node_set("xmin")) EXPECT_EQ(piece.mesh.nodes(0, n), box.lower[0]);
    }
    for (int e = 0; e < whole.num_elements(); ++e) ASSERT_EQ(element_seen[e], 1) << "element " << e;
    EXPECT_EQ(static_cast<int>(holders.size()), whole.num_nodes());
    EXPECT_EQ(static_cast<int>(owner_of.size()), whole.num_nodes());
    for (const auto& [id, parts_having] : holders) EXPECT_EQ(owner_of[id], *parts_having.begin()) << "node " << id;
    EXPECT_EQ(boundary_owned, static_cast<int>(whole.node_set("boundary").size()));
  }
}

INSTANTIATE_TEST_SUITE_P(Elements, BoxPieces,
                         ::testing::Values(PieceCase{CellType::Tetrahedron, 1}, PieceCase{CellType::Tetrahedron, 2},
                                           PieceCase{CellType::Tetrahedron, 3}, PieceCase{CellType::Hexahedron, 1},
                                           PieceCase{CellType::Hexahedron, 2}));

// Balanced blocks: cube counts per part within the rounding of the proportional
// cuts; a box with too few cubes for the parts is refused with a message.
TEST(BoxBlocks, TileTheBoxAndRefuseTooManyParts) {
  const BoxSpec box = unit_cube(8);
  const auto blocks = box_blocks(box, 8);
  int total = 0;
  for (const auto& b : blocks) {
    const int cubes = (b[0][1] - b[0][0]) * (b[1][1] - b[1][0]) * (b[2][1] - b[2][0]);
    EXPECT_EQ(cubes, 64);  // 8^3 / 8: three mid-plane cuts
    total += cubes;
  }
  EXPECT_EQ(total, 512);
  EXPECT_THROW(box_blocks(unit_cube(1), 2), MeshError);
  EXPECT_THROW(box_piece(box, CellType::Tetrahedron, 1, 2, 2), MeshError);
}

}  // namespace
}  // namespace hofem
