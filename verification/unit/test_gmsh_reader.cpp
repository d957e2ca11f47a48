// Gmsh .msh reader: hand-written meshes under data/gmsh_*.msh (each explains itself in
// a $Comments section, which the reader must skip) and one test per error class; every
// error must name the origin and the line of the fault.
#include <gtest/gtest.h>

#include <Eigen/LU>  // determinant
#include <fstream>
#include <sstream>
#include <string>

#include "basis/lagrange_nodes.hpp"
#include "io/gmsh_reader.hpp"
#include "quadrature/cell_type.hpp"

namespace hofem {
namespace {

std::string data_path(const std::string& name) { return std::string(HOFEM_TEST_DATA_DIR) + "/" + name; }

std::string read_text(const std::string& name) {
  std::ifstream file(data_path(name), std::ios::binary);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

using Sets = std::map<std::string, std::vector<int>>;

void expect_same_mesh(const Mesh& a, const Mesh& b) {
  EXPECT_EQ(a.cell, b.cell);
  EXPECT_EQ(a.order, b.order);
  EXPECT_EQ(a.nodes, b.nodes);
  EXPECT_EQ(a.elements, b.elements);
  EXPECT_EQ(a.node_sets, b.node_sets);
  EXPECT_EQ(a.element_sets, b.element_sets);
}

// Signed volume of the tetrahedron spanned by the first four nodes of element e.
double tet_volume(const Mesh& m, int e) {
  Eigen::Matrix3d j;
  for (int k = 0; k < 3; ++k) j.col(k) = m.nodes.col(m.elements(k + 1, e)) - m.nodes.col(m.elements(0, e));
  return j.determinant() / 6;
}

// --- meshes that must be read -------------------------------------------------------

TEST(GmshReader, Tet4CubeV41) {
  const Mesh m = read_gmsh(data_path("gmsh_cube_tet4_v41.msh"));
  EXPECT_EQ(m.cell, CellType::Tetrahedron);
  EXPECT_EQ(m.order, 1);
  ASSERT_EQ(m.num_nodes(), 8);  // node 50 (used by nothing) is dropped
  ASSERT_EQ(m.num_elements(), 6);
  ASSERT_EQ(m.nodes_per_element(), 4);
  // Tag t -> id t - 1: file order, with node 50 left out.
  const double corners[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (int i = 0; i < 8; ++i)
    for (int d = 0; d < 3; ++d) EXPECT_EQ(m.nodes(d, i), corners[i][d]) << "node " << i;
  // Connectivity in file order, node order within each element unchanged.
  const int tets[6][4] = {{0, 1, 2, 6}, {0, 3, 7, 6}, {0, 4, 5, 6}, {0, 1, 6, 5}, {0, 3, 6, 2}, {0, 4, 6, 7}};
  double volume = 0;
  for (int e = 0; e < 6; ++e) {
    for (int k = 0; k < 4; ++k) EXPECT_EQ(m.elements(k, e), tets[e][k]) << "element " << e;
    EXPECT_GT(tet_volume(m, e), 0) << "element " << e;
    volume += tet_volume(m, e);
  }
  EXPECT_NEAR(volume, 1.0, 1e-15);
  const Sets nodes{
      {"origin", {0}}, {"physical_7", {0, 1}}, {"bottom", {0, 1, 2, 3}}, {"solid", {0, 1, 2, 3, 4, 5, 6, 7}}};
  EXPECT_EQ(m.node_sets, nodes);
  EXPECT_EQ(m.element_sets, (Sets{{"solid", {0, 1, 2, 3, 4, 5}}}));
}

TEST(GmshReader, Tet4CubeV22GivesTheSameMeshAsV41) {
  expect_same_mesh(read_gmsh(data_path("gmsh_cube_tet4_v22.msh")), read_gmsh(data_path("gmsh_cube_tet4_v41.msh")));
}

TEST(GmshReader, WindowsLineEndingsAndBlankLinesAreAccepted) {
  std::string crlf;
  for (const char c : read_text("gmsh_cube_tet4_v22.msh"))
    crlf += c == '\n' ? std::string("\r\n\n") : std::string(1, c);
  expect_same_mesh(read_gmsh_text(crlf, "crlf.msh"), read_gmsh(data_path("gmsh_cube_tet4_v41.msh")));
}

// Tet10: each element's nodes must be the affine image of hofem's own Gmsh-ordered
// reference Tet10 nodes, i.e. mid-edge node k sits on Gmsh edge k of its element.
TEST(GmshReader, Tet10CubeHasItsMidEdgeNodesInGmshOrder) {
  const Mesh m = read_gmsh(data_path("gmsh_cube_tet10_v41.msh"));
  EXPECT_EQ(m.cell, CellType::Tetrahedron);
  EXPECT_EQ(m.order, 2);
  EXPECT_EQ(m.num_nodes(), 27);
  ASSERT_EQ(m.num_elements(), 6);
  ASSERT_EQ(m.nodes_per_element(), 10);
  const Eigen::MatrixXd ref = simplex_lagrange_nodes(CellType::Tetrahedron, 2);  // 3 x 10, unit tet
  for (int e = 0; e < 6; ++e) {
    EXPECT_GT(tet_volume(m, e), 0);
    const Eigen::Vector3d x0 = m.nodes.col(m.elements(0, e));
    Eigen::Matrix3d j;
    for (int k = 0; k < 3; ++k) j.col(k) = m.nodes.col(m.elements(k + 1, e)) - x0;
    for (int k = 0; k < 10; ++k)
      EXPECT_TRUE(m.nodes.col(m.elements(k, e)).isApprox(x0 + j * ref.col(k), 1e-15))
          << "element " << e << " node " << k;
  }
  // "bottom": 4 corners + 5 mid-edge nodes (4 cube edges and the diagonal 1-3).
  EXPECT_EQ(m.node_set("bottom").size(), 9u);
  for (const int n : m.node_set("bottom")) EXPECT_EQ(m.nodes(2, n), 0.0);
  EXPECT_EQ(m.node_set("solid").size(), 27u);
  EXPECT_EQ(m.element_sets, (Sets{{"solid", {0, 1, 2, 3, 4, 5}}}));
}

TEST(GmshReader, Tet20NodesMatchTheGmshLattice) {
  const Mesh m = read_gmsh(data_path("gmsh_tet20_v22.msh"));
  EXPECT_EQ(m.cell, CellType::Tetrahedron);
  EXPECT_EQ(m.order, 3);
  ASSERT_EQ(m.num_elements(), 1);
  ASSERT_EQ(m.nodes_per_element(), 20);
  const auto lattice = tetrahedron_lattice(3);  // integer points, Gmsh order
  for (int k = 0; k < 20; ++k) {
    EXPECT_EQ(m.elements(k, 0), k);
    for (int d = 0; d < 3; ++d) EXPECT_EQ(m.nodes(d, k), lattice[k][d]) << "node " << k;
  }
  EXPECT_TRUE(m.node_sets.empty());  // no physical groups
  EXPECT_TRUE(m.element_sets.empty());
}

TEST(GmshReader, Hex8) {
  const Mesh m = read_gmsh(data_path("gmsh_hex8_v41.msh"));
  EXPECT_EQ(m.cell, CellType::Hexahedron);
  EXPECT_EQ(m.order, 1);
  ASSERT_EQ(m.num_elements(), 1);
  ASSERT_EQ(m.num_nodes(), 8);
  const Eigen::MatrixXd ref = hex_nodes(1);  // [-1,1]^3 in Gmsh order
  for (int k = 0; k < 8; ++k) {
    EXPECT_EQ(m.elements(k, 0), k);
    EXPECT_TRUE(m.nodes.col(k).isApprox((ref.col(k).array() + 1).matrix() / 2)) << "node " << k;
  }
  EXPECT_EQ(m.node_sets, (Sets{{"top", {4, 5, 6, 7}}, {"block", {0, 1, 2, 3, 4, 5, 6, 7}}}));
  EXPECT_EQ(m.element_sets, (Sets{{"block", {0}}}));
}

TEST(GmshReader, Hex20) {
  const Mesh m = read_gmsh(data_path("gmsh_hex20_v22.msh"));
  EXPECT_EQ(m.cell, CellType::Hexahedron);
  EXPECT_EQ(m.order, 2);
  ASSERT_EQ(m.num_elements(), 1);
  ASSERT_EQ(m.num_nodes(), 20);
  const Eigen::MatrixXd ref = hex_nodes(2);  // [-1,1]^3; the file's hex is [0,2]^3
  for (int k = 0; k < 20; ++k) {
    EXPECT_EQ(m.elements(k, 0), k);
    EXPECT_TRUE(m.nodes.col(k).isApprox((ref.col(k).array() + 1).matrix())) << "node " << k;
  }
  EXPECT_EQ(m.node_set("top"), (std::vector<int>{4, 5, 6, 7, 16, 17, 18, 19}));
  EXPECT_EQ(m.element_sets, (Sets{{"block", {0}}}));
}

// --- malformed input ----------------------------------------------------------------

// Passes when read_gmsh_text(text, "bad.msh") throws a MeshError whose message starts
// with "bad.msh:<line>: " and contains `what`.
testing::AssertionResult fails_at(const std::string& text, int line, const std::string& what) {
  std::string message;
  try {
    read_gmsh_text(text, "bad.msh");
    return testing::AssertionFailure() << "no error";
  } catch (const MeshError& e) {
    message = e.what();
  }
  const std::string prefix = "bad.msh:" + std::to_string(line) + ": ";
  if (message.rfind(prefix, 0) != 0 || message.find(what) == std::string::npos)
    return testing::AssertionFailure() << "message: " << message << "\nexpected prefix '" << prefix << "' and '" << what
                                       << "'";
  return testing::AssertionSuccess();
}

// A valid 2.2 file with one Tet4; kNodes22 is lines 4-10, the element line is 13.
const std::string kHead22 = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
const std::string kNodes22 = "$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n";
std::string elements22(const std::string& lines, int count = 1) {
  return "$Elements\n" + std::to_string(count) + "\n" + lines + "$EndElements\n";
}
const std::string kTet22 = kHead22 + kNodes22 + elements22("1 4 2 1 1 1 2 3 4\n");

// The same in 4.1: nodes are lines 4-15, the element line is 19.
const std::string kHead41 = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
const std::string kNodes41 = "$Nodes\n1 4 1 4\n3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n$EndNodes\n";
const std::string kElements41 = "$Elements\n1 1 1 1\n3 1 4 1\n1 1 2 3 4\n$EndElements\n";

TEST(GmshReaderErrors, TheValidBaseFilesParse) {
  const Mesh m22 = read_gmsh_text(kTet22, "ok.msh"), m41 = read_gmsh_text(kHead41 + kNodes41 + kElements41, "ok.msh");
  EXPECT_EQ(m22.nodes, m41.nodes);
  EXPECT_EQ(m22.elements, m41.elements);
  // The 2.2 tet has physical tag 1 and no $PhysicalNames; the 4.1 one has no $Entities.
  EXPECT_EQ(m22.node_sets, (Sets{{"physical_1", {0, 1, 2, 3}}}));
  EXPECT_EQ(m22.element_sets, (Sets{{"physical_1", {0}}}));
  EXPECT_TRUE(m41.node_sets.empty());
}

TEST(GmshReaderErrors, MissingMeshFormat) {
  EXPECT_TRUE(fails_at(kNodes22, 1, "missing $MeshFormat"));
  EXPECT_TRUE(fails_at("", 1, "missing $MeshFormat"));
  EXPECT_TRUE(fails_at("\n\nsolid cube\n", 3, "missing $MeshFormat"));  // e.g. an STL file
}

TEST(GmshReaderErrors, UnsupportedVersionNamesTheSupportedOnes) {
  EXPECT_TRUE(fails_at("$MeshFormat\n4.0 0 8\n$EndMeshFormat\n", 2, "supported versions are 4.1 and 2.2"));
  EXPECT_TRUE(fails_at("$MeshFormat\n4.1 0\n$EndMeshFormat\n", 2, "expected 3 values"));
}

TEST(GmshReaderErrors, BinaryFilesAreRejected) {
  using namespace std::string_literals;  // the binary file holds NUL bytes
  EXPECT_TRUE(
      fails_at("$MeshFormat\n4.1 1 8\n\x01\0\0\0\n$EndMeshFormat\n$Nodes\n\0\xff\n"s, 2, "only ASCII is supported"));
}

TEST(GmshReaderErrors, TruncatedSections) {
  // The file stops inside $Nodes: the error is on the last line.
  EXPECT_TRUE(fails_at(kHead22 + "$Nodes\n2\n1 0 0 0\n2 1 0 0\n", 7, "$EndNodes missing"));
  // Fewer nodes than announced: $EndNodes comes too early.
  EXPECT_TRUE(fails_at(kHead22 + "$Nodes\n3\n1 0 0 0\n2 1 0 0\n$EndNodes\n", 8, "fewer entries than announced"));
  // More nodes than announced.
  EXPECT_TRUE(fails_at(kHead22 + "$Nodes\n1\n1 0 0 0\n2 1 0 0\n$EndNodes\n", 7, "expected $EndNodes"));
  // 4.1: the block announces 4 nodes but lists only 3 coordinate lines.
  EXPECT_TRUE(fails_at(kHead41 + "$Nodes\n1 4 1 4\n3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n$EndNodes\n", 14,
                       "truncated $Nodes section"));
  // 4.1: the header announces 5 nodes, the blocks hold 4 (error on the header, line 5).
  std::string five = kNodes41;
  five.replace(five.find("1 4 1 4"), 7, "1 5 1 4");
  EXPECT_TRUE(fails_at(kHead41 + five + kElements41, 5, "announces 5 nodes but its blocks hold 4"));
  // $Elements without its end, and an unknown section without its end.
  EXPECT_TRUE(fails_at(kHead22 + kNodes22 + "$Elements\n1\n1 4 2 1 1 1 2 3 4\n", 13, "$EndElements missing"));
  EXPECT_TRUE(fails_at(kTet22 + "$Comments\nno end\n", 16, "$EndComments missing"));
  EXPECT_TRUE(fails_at(kHead22 + kNodes22, 10, "no $Elements section"));
}

TEST(GmshReaderErrors, NonNumericTokens) {
  EXPECT_TRUE(
      fails_at(kHead22 + "$Nodes\n1\n1 0 zero 0\n$EndNodes\n", 6, "expected a number (node coordinate), got 'zero'"));
  EXPECT_TRUE(fails_at(kHead22 + "$Nodes\n1\nx1 0 0 0\n$EndNodes\n", 6, "expected an integer (node tag), got 'x1'"));
  EXPECT_TRUE(fails_at(kHead22 + "$Nodes\nmany\n$EndNodes\n", 5, "got 'many'"));
  EXPECT_TRUE(fails_at(kHead22 + kNodes22 + elements22("1 4 2 1 1 1 2 3 4.5\n"), 13, "got '4.5'"));
  EXPECT_TRUE(fails_at(kHead41 + kNodes41 + "$Elements\n1 1 1 1\n3 1 tet 1\n1 1 2 3 4\n$EndElements\n", 18,
                       "expected an integer (element type), got 'tet'"));
}

TEST(GmshReaderErrors, ElementReferencesAnUnknownNode) {
  EXPECT_TRUE(fails_at(kHead22 + kNodes22 + elements22("1 4 2 1 1 1 2 3 99\n"), 13, "node tag 99"));
  std::string bad = kElements41;
  bad.replace(bad.find("1 1 2 3 4"), 9, "1 1 2 3 7");
  EXPECT_TRUE(fails_at(kHead41 + kNodes41 + bad, 19, "node tag 7, which is not defined"));
}

TEST(GmshReaderErrors, DuplicateNodeTags) {
  EXPECT_TRUE(fails_at(kHead22 + "$Nodes\n2\n1 0 0 0\n1 1 0 0\n$EndNodes\n", 7,
                       "duplicate node tag 1 (first defined at line 6)"));
  EXPECT_TRUE(fails_at(kHead41 + "$Nodes\n2 2 1 1\n3 1 0 1\n1\n0 0 0\n3 1 0 1\n1\n1 0 0\n$EndNodes\n", 10,
                       "duplicate node tag 1"));
}

TEST(GmshReaderErrors, WrongNumberOfNodesForTheElementType) {
  EXPECT_TRUE(fails_at(kHead22 + kNodes22 + elements22("1 4 2 1 1 1 2 3\n"), 13,
                       "Tet4 (element type 4) has 4 nodes, but this element lists 3"));
  EXPECT_TRUE(
      fails_at(kHead22 + kNodes22 + elements22("1 11 2 1 1 1 2 3 4\n"), 13, "Tet10 (element type 11) has 10 nodes"));
  std::string bad = kElements41;
  bad.replace(bad.find("1 1 2 3 4"), 9, "1 1 2 3 4 4");
  EXPECT_TRUE(fails_at(kHead41 + kNodes41 + bad, 19, "this element lists 5"));
}

TEST(GmshReaderErrors, NonFiniteCoordinates) {
  for (const std::string x : {"nan", "inf", "-inf", "NaN"})
    EXPECT_TRUE(fails_at(kHead22 + "$Nodes\n1\n1 0 " + x + " 0\n$EndNodes\n", 6, "is not finite")) << x;
  EXPECT_TRUE(fails_at(kHead22 + "$Nodes\n1\n1 0 1e999 0\n$EndNodes\n", 6, "out of range"));
}

TEST(GmshReaderErrors, MissingFileNamesThePath) {
  const std::string path = "/nonexistent/hofem/mesh.msh";
  try {
    read_gmsh(path);
    ADD_FAILURE() << "no error";
  } catch (const MeshError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_gmsh(HOFEM_TEST_DATA_DIR), MeshError);  // a directory
}

TEST(GmshReaderErrors, VolumeElementTypes) {
  // Tet4 on line 13, then a Hex8 on line 14.
  EXPECT_TRUE(fails_at(kHead22 + kNodes22 + elements22("1 4 2 1 1 1 2 3 4\n2 5 2 1 1 1 2 3 4 1 2 3 4\n", 2), 14,
                       "mixes volume element types: Hex8 (type 5) here, Tet4 (type 4) at line 13"));
  // Only a physical triangle: no volume; the error points at $Elements (line 11).
  EXPECT_TRUE(fails_at(kHead22 + kNodes22 + elements22("1 2 2 1 1 1 2 3\n"), 11, "no volume elements"));
  // A prism (type 6) is a volume hofem does not read, with or without a physical tag.
  EXPECT_TRUE(fails_at(kHead22 + kNodes22 + elements22("1 6 0 1 2 3 4 1 2\n"), 13, "unsupported element type 6"));
  // A 9-node quad (type 10) in a physical group is an error; outside any group it is ignored.
  EXPECT_TRUE(fails_at(kHead22 + kNodes22 + elements22("1 10 2 5 1 1 2 3 4 1 2 3 4 1\n1 4 0 1 2 3 4\n", 2), 13,
                       "unsupported element type 10"));
  const Mesh m = read_gmsh_text(kHead22 + kNodes22 + elements22("1 10 0 1 2 3 4 1 2 3 4 1\n1 4 0 1 2 3 4\n", 2), "ok");
  EXPECT_EQ(m.num_elements(), 1);
  // 4.1: an element block on an entity that $Entities does not list.
  const std::string entities = "$Entities\n0 0 0 1\n2 0 0 0 1 1 1 0 0\n$EndEntities\n";
  EXPECT_TRUE(
      fails_at(kHead41 + entities + kNodes41 + kElements41, 23, "entity (dimension 3, tag 1) is not in $Entities"));
}

TEST(GmshReaderErrors, StrayTextBetweenSectionsAndUnknownSectionsSkipped) {
  EXPECT_TRUE(fails_at(kTet22 + "hello\n", 15, "expected a section header"));
  EXPECT_TRUE(fails_at(kTet22 + "$EndNodes\n", 15, "without a matching opening"));
  EXPECT_TRUE(fails_at(kTet22 + kNodes22, 15, "second $Nodes section (the first is at line 4)"));
  // Sections hofem does not use are skipped, wherever they are.
  const std::string other =
      "$Comments\nfree text, $Nodes inside is not a section\n$EndComments\n$Periodic\n0\n$EndPeriodic\n";
  expect_same_mesh(read_gmsh_text(kHead22 + other + kNodes22 + other + elements22("1 4 2 1 1 1 2 3 4\n") + other, "ok"),
                   read_gmsh_text(kTet22, "ok"));
}

// Garbage must give MeshError, never a crash, another exception or an out-of-bounds
// read (run under scripts/test --sanitize): every prefix of every test mesh, and every
// byte replaced by characters that break numbers, lines and sections.
TEST(GmshReaderErrors, TruncatedAndCorruptedFilesOnlyThrowMeshError) {
  int errors = 0, parsed = 0;
  const auto attempt = [&](const std::string& text) {
    try {
      read_gmsh_text(text, "fuzz.msh");
      ++parsed;
    } catch (const MeshError& e) {
      ++errors;
      EXPECT_EQ(std::string(e.what()).rfind("fuzz.msh:", 0), 0u) << e.what();
    } catch (const std::exception& e) {
      ADD_FAILURE() << "unexpected exception: " << e.what() << "\ninput:\n" << text;
    }
  };
  for (const char* name : {"gmsh_cube_tet4_v41.msh", "gmsh_cube_tet4_v22.msh", "gmsh_cube_tet10_v41.msh",
                           "gmsh_tet20_v22.msh", "gmsh_hex8_v41.msh", "gmsh_hex20_v22.msh"}) {
    const std::string text = read_text(name);
    ASSERT_FALSE(text.empty()) << name;
    for (std::size_t n = 0; n < text.size(); ++n) attempt(text.substr(0, n));
    for (std::size_t i = 0; i < text.size(); ++i)
      for (const char c : {'x', '9', '-', '\n', '$', '\0'}) {
        std::string bad = text;
        bad[i] = c;
        attempt(bad);
      }
  }
  EXPECT_GT(errors, 0);
  EXPECT_GT(parsed, 0);
}

}  // namespace
}  // namespace hofem
