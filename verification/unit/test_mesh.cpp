// Box meshes, order upgrade (shared nodes), quality checks and their errors.
#include "mesh/box_mesh.hpp"
#include "io/gmsh_reader.hpp"
#include "mesh/mesh_quality.hpp"
#include "mesh/mesh_upgrade.hpp"

#include <Eigen/LU>
#include <gtest/gtest.h>

#include <map>
#include <set>

namespace hofem {
namespace {

TEST(BoxMesh, CountsVolumesAndNodeSets) {
  const BoxSpec box{{0, 0, 0}, {2, 1, 3}, {2, 3, 4}};
  const Mesh tets = box_tet_mesh(box);
  EXPECT_EQ(tets.num_elements(), 6 * 24);
  EXPECT_EQ(tets.num_nodes(), 3 * 4 * 5);
  const Mesh hexes = box_hex_mesh(box);
  EXPECT_EQ(hexes.num_elements(), 24);
  // Every tetrahedron positively oriented and the volumes add up to the box's.
  double volume = 0.0;
  for (int e = 0; e < tets.num_elements(); ++e) {
    Eigen::Matrix3d J;
    for (int c = 0; c < 3; ++c) J.col(c) = tets.nodes.col(tets.elements(c + 1, e)) - tets.nodes.col(tets.elements(0, e));
    EXPECT_GT(J.determinant(), 0.0) << "element " << e;
    volume += J.determinant() / 6.0;
  }
  EXPECT_NEAR(volume, 6.0, 1e-12);
  EXPECT_EQ(tets.node_set("xmin").size(), 4u * 5u);
  EXPECT_EQ(tets.node_set("boundary").size(), 60u - 2u * 1u * 3u);  // interior: 1 x 2 x 3
  EXPECT_THROW(tets.node_set("top"), MeshError);
  EXPECT_THROW(box_tet_mesh(BoxSpec{{0, 0, 0}, {1, 1, 1}, {0, 1, 1}}), MeshError);
  EXPECT_THROW(box_tet_mesh(BoxSpec{{0, 0, 0}, {-1, 1, 1}, {1, 1, 1}}), MeshError);
}

// Upgrading shares every edge/face node: the node count must equal the number of
// distinct lattice points of the whole box at the finer spacing h/p.
TEST(MeshUpgrade, SharedNodesMatchTheFineLattice) {
  for (int p = 2; p <= 4; ++p) {
    const int n = 3;
    const Mesh m = box_mesh(unit_cube(n), CellType::Tetrahedron, p);
    EXPECT_EQ(m.num_nodes(), (n * p + 1) * (n * p + 1) * (n * p + 1)) << "order " << p;
    // All nodes on the fine lattice, none duplicated.
    std::set<std::array<long, 3>> seen;
    for (int i = 0; i < m.num_nodes(); ++i) {
      std::array<long, 3> k{};
      for (int c = 0; c < 3; ++c) {
        const double v = m.nodes(c, i) * n * p;
        k[c] = std::lround(v);
        EXPECT_NEAR(v, static_cast<double>(k[c]), 1e-9);
      }
      EXPECT_TRUE(seen.insert(k).second);
    }
    // Boundary set = nodes on the cube's faces.
    const int fine = n * p + 1;
    EXPECT_EQ(static_cast<int>(m.node_set("boundary").size()), fine * fine * fine - (fine - 2) * (fine - 2) * (fine - 2));
  }
  const Mesh hex20 = box_mesh(unit_cube(2), CellType::Hexahedron, 2);
  EXPECT_EQ(hex20.num_nodes(), 27 + 54);  // 3^3 vertices + 54 edges of a 2x2x2 grid
}

// The topological upgrade (not the box's geometric re-labelling): an interior
// edge joining two boundary vertices must not be marked as boundary.
TEST(MeshUpgrade, TopologicalBoundaryExcludesInteriorEdges) {
  const Mesh linear = box_tet_mesh(unit_cube(1));  // every vertex is on the boundary
  const Mesh quad = upgrade_order(linear, 2);
  // The cube diagonal (0,0,0)-(1,1,1) is interior: its midpoint is the centre.
  int centre = -1;
  for (int i = 0; i < quad.num_nodes(); ++i)
    if ((quad.nodes.col(i) - Eigen::Vector3d(0.5, 0.5, 0.5)).norm() < 1e-12) centre = i;
  ASSERT_GE(centre, 0);
  const auto& b = quad.node_set("boundary");
  EXPECT_FALSE(std::binary_search(b.begin(), b.end(), centre));
  EXPECT_EQ(b.size(), static_cast<size_t>(quad.num_nodes() - 1));
  // A face group keeps its face's edge nodes and gains none from elsewhere.
  const auto& xmin = quad.node_set("xmin");
  for (int i : xmin) EXPECT_NEAR(quad.nodes(0, i), 0.0, 1e-15);
  EXPECT_EQ(xmin.size(), 9u);
  EXPECT_THROW(upgrade_order(quad, 3), MeshError);  // input must be linear
}

TEST(MeshQuality, ReportsAnglesAndRejectsInvertedAndDegenerateElements) {
  Mesh m = box_tet_mesh(unit_cube(2));
  const MeshQuality q = measure_quality(m);
  EXPECT_NEAR(q.min_dihedral_degrees, 45.0, 1e-9);  // Kuhn tetrahedra: 45, 60, 90 degrees
  EXPECT_NEAR(q.max_dihedral_degrees, 90.0, 1e-9);
  EXPECT_EQ(q.inverted_elements, 0);
  EXPECT_NO_THROW(validate_mesh(m));
  std::swap(m.elements(0, 5), m.elements(1, 5));  // invert element 5
  try {
    validate_mesh(m);
    FAIL() << "inverted element accepted";
  } catch (const MeshError& e) {
    EXPECT_NE(std::string(e.what()).find("element 5: inverted"), std::string::npos) << e.what();
  }
  Mesh flat = box_tet_mesh(unit_cube(1));
  flat.nodes.col(flat.elements(3, 2)) = flat.nodes.col(flat.elements(0, 2));  // collapse element 2... and neighbours
  EXPECT_THROW(validate_mesh(flat), MeshError);
  Mesh bad_index = box_tet_mesh(unit_cube(1));
  bad_index.elements(2, 3) = 999;
  try {
    validate_mesh(bad_index);
    FAIL();
  } catch (const MeshError& e) {
    EXPECT_NE(std::string(e.what()).find("element 3: node index 999 out of range"), std::string::npos) << e.what();
  }
  Mesh nan_mesh = box_tet_mesh(unit_cube(1));
  nan_mesh.nodes(0, 0) = std::nan("");
  EXPECT_THROW(validate_mesh(nan_mesh), MeshError);
}

}  // namespace
}  // namespace hofem

namespace hofem {
namespace {

// Physical groups survive the upgrade: a volume group gets every node, a curve
// group its edge nodes, a surface group its edge and face nodes.
TEST(MeshUpgrade, GmshPhysicalGroupsGainTheirHighOrderNodes) {
  const Mesh linear = read_gmsh(std::string(HOFEM_TEST_DATA_DIR) + "/gmsh_cube_tet4_v41.msh");
  const Mesh cubic = upgrade_order(linear, 3);
  EXPECT_EQ(cubic.node_set("solid").size(), static_cast<size_t>(cubic.num_nodes()));
  EXPECT_EQ(cubic.node_set("physical_7").size(), linear.node_set("physical_7").size() + 2);  // one edge, 2 nodes
  for (int n : cubic.node_set("bottom")) EXPECT_NEAR(cubic.nodes(2, n), 0.0, 1e-15);
  EXPECT_EQ(cubic.node_set("bottom").size(), 16u);  // the z = 0 square split in two triangles, cubic: 4 x 4 lattice
}

}  // namespace
}  // namespace hofem
