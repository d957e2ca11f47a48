// VTK output (core/io/vtu_writer): Gmsh -> VTK node orderings checked against the
// coordinates VTK documents for each ordering, and the written .vtu/.pvd files read
// back with a small XML reader (no VTK needed).
#include "io/vtu_writer.hpp"

#include "basis/lagrange_nodes.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <numbers>
#include <numeric>
#include <iterator>

namespace hofem {
namespace {

using Coords = std::vector<std::array<double, 3>>;

// Gmsh node perm[k] must sit where VTK puts its point k. Hex coordinates in VTK's
// tables are on [0,1]^3, hofem's on [-1,1]^3.
void expect_vtk_coordinates(CellType cell, int order, const Coords& vtk) {
  const Eigen::MatrixXd gmsh = cell == CellType::Hexahedron ? hex_nodes(order) : simplex_lagrange_nodes(cell, order);
  const std::vector<int> perm = gmsh_to_vtk_permutation(cell, order);
  ASSERT_EQ(perm.size(), vtk.size());
  for (size_t k = 0; k < vtk.size(); ++k)
    for (int c = 0; c < 3; ++c) {
      const double want = cell == CellType::Hexahedron ? 2 * vtk[k][c] - 1 : vtk[k][c];
      EXPECT_NEAR(gmsh(c, perm[k]), want, 1e-15) << "VTK point " << k << " coordinate " << c;
    }
}

Coords lattice_table(const std::vector<std::array<int, 3>>& ijk, double p) {
  Coords x;
  for (const auto& q : ijk) x.push_back({q[0] / p, q[1] / p, q[2] / p});
  return x;
}

TEST(VtuPermutation, IsAPermutationForEverySupportedCell) {
  std::vector<std::pair<CellType, int>> cells{{CellType::Hexahedron, 1}, {CellType::Hexahedron, 2}};
  for (int p = 1; p <= 10; ++p) cells.emplace_back(CellType::Tetrahedron, p);
  for (const auto& [cell, order] : cells) {
    std::vector<int> perm = gmsh_to_vtk_permutation(cell, order);
    ASSERT_EQ(static_cast<int>(perm.size()), nodes_per_element(cell, order)) << name(cell) << order;
    std::sort(perm.begin(), perm.end());
    std::vector<int> iota(perm.size());
    std::iota(iota.begin(), iota.end(), 0);
    EXPECT_EQ(perm, iota) << name(cell) << " order " << order;
  }
  EXPECT_THROW(gmsh_to_vtk_permutation(CellType::Hexahedron, 3), std::invalid_argument);
  EXPECT_THROW(gmsh_to_vtk_permutation(CellType::Triangle, 2), std::invalid_argument);
  EXPECT_THROW(gmsh_to_vtk_permutation(CellType::Tetrahedron, 0), std::invalid_argument);
}

TEST(VtuPermutation, CellTypeCodes) {  // Common/DataModel/vtkCellType.h
  EXPECT_EQ(vtk_cell_type(CellType::Tetrahedron, 1), 10);  // VTK_TETRA
  EXPECT_EQ(vtk_cell_type(CellType::Tetrahedron, 2), 24);  // VTK_QUADRATIC_TETRA
  for (int p = 3; p <= 8; ++p) EXPECT_EQ(vtk_cell_type(CellType::Tetrahedron, p), 71);  // VTK_LAGRANGE_TETRAHEDRON
  EXPECT_EQ(vtk_cell_type(CellType::Hexahedron, 1), 12);  // VTK_HEXAHEDRON
  EXPECT_EQ(vtk_cell_type(CellType::Hexahedron, 2), 25);  // VTK_QUADRATIC_HEXAHEDRON
}

// vtkTetra: the Gmsh vertex order. vtkQuadraticTetra.cxx, vtkQTetraCellPCoords
// (edges (0,1),(1,2),(2,0),(0,3),(1,3),(2,3)): Gmsh Tet10 with nodes 8 and 9 swapped.
TEST(VtuPermutation, Tet4AndTet10MatchVtkTetraAndQuadraticTetra) {
  expect_vtk_coordinates(CellType::Tetrahedron, 1, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
  EXPECT_EQ(gmsh_to_vtk_permutation(CellType::Tetrahedron, 1), (std::vector<int>{0, 1, 2, 3}));
  expect_vtk_coordinates(CellType::Tetrahedron, 2,
                         {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {.5, 0, 0}, {.5, .5, 0}, {0, .5, 0},
                          {0, 0, .5}, {.5, 0, .5}, {0, .5, .5}});
  EXPECT_EQ(gmsh_to_vtk_permutation(CellType::Tetrahedron, 2), (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7, 9, 8}));
}

// vtkHexahedron.cxx, vtkHexahedronCellPCoords; vtkQuadraticHexahedron.cxx,
// vtkQHexCellPCoords (edges (0,1),(1,2),(2,3),(3,0),(4,5),(5,6),(6,7),(7,4),(0,4),
// (1,5),(2,6),(3,7), vtkQuadraticHexahedron.h).
TEST(VtuPermutation, Hex8AndHex20MatchVtkHexahedronAndQuadraticHexahedron) {
  expect_vtk_coordinates(CellType::Hexahedron, 1,
                         {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}});
  expect_vtk_coordinates(CellType::Hexahedron, 2,
                         {{0, 0, 0},  {1, 0, 0},  {1, 1, 0},  {0, 1, 0},  {0, 0, 1},  {1, 0, 1},  {1, 1, 1},
                          {0, 1, 1},  {.5, 0, 0}, {1, .5, 0}, {.5, 1, 0}, {0, .5, 0}, {.5, 0, 1}, {1, .5, 1},
                          {.5, 1, 1}, {0, .5, 1}, {0, 0, .5}, {1, 0, .5}, {1, 1, .5}, {0, 1, .5}});
  EXPECT_EQ(gmsh_to_vtk_permutation(CellType::Hexahedron, 2),
            (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 13, 9, 16, 18, 19, 17, 10, 12, 14, 15}));
}

// VTK_LAGRANGE_TETRAHEDRON of order 3, lattice coordinates x 3, worked out by hand from
// vtkHigherOrderTetra::BarycentricIndex (VertexMaxCoords, EdgeVertices, FaceBCoords,
// FaceMinCoord): vertices; edges 0-1, 1-2, 2-0, 0-3, 1-3, 2-3; one centroid per face,
// faces (0,1,3), (1,2,3), (2,0,3), (0,2,1).
TEST(VtuPermutation, Tet20MatchesVtkLagrangeTetra) {
  const std::vector<std::array<int, 3>> vtk{
      {0, 0, 0}, {3, 0, 0}, {0, 3, 0}, {0, 0, 3},                          // vertices
      {1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 2, 0}, {0, 2, 0}, {0, 1, 0},    // edges 0-1, 1-2, 2-0
      {0, 0, 1}, {0, 0, 2}, {2, 0, 1}, {1, 0, 2}, {0, 2, 1}, {0, 1, 2},    // edges 0-3, 1-3, 2-3
      {1, 0, 1}, {1, 1, 1}, {0, 1, 1}, {1, 1, 0}};                         // faces
  EXPECT_EQ(vtk_tetrahedron_lattice(3), vtk);
  expect_vtk_coordinates(CellType::Tetrahedron, 3, lattice_table(vtk, 3));
}

// Order 4 (x 4), same source. Each face holds an order-1 triangle in VTK triangle
// order; face 1's triangle starts at vertex 2 (FaceBCoords {2,0,1}: triangle
// vertices 2, 3, 1), face 2's at vertex 0 (triangle 0, 3, 2), face 3's is 0, 2, 1.
TEST(VtuPermutation, Tet35MatchesVtkLagrangeTetra) {
  const std::vector<std::array<int, 3>> vtk{
      {0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {0, 0, 4},                          // vertices
      {1, 0, 0}, {2, 0, 0}, {3, 0, 0}, {3, 1, 0}, {2, 2, 0}, {1, 3, 0},    // edges 0-1, 1-2
      {0, 3, 0}, {0, 2, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 2}, {0, 0, 3},    // edges 2-0, 0-3
      {3, 0, 1}, {2, 0, 2}, {1, 0, 3}, {0, 3, 1}, {0, 2, 2}, {0, 1, 3},    // edges 1-3, 2-3
      {1, 0, 1}, {2, 0, 1}, {1, 0, 2}, {1, 2, 1}, {1, 1, 2}, {2, 1, 1},    // faces 0, 1
      {0, 1, 1}, {0, 1, 2}, {0, 2, 1}, {1, 1, 0}, {1, 2, 0}, {2, 1, 0},    // faces 2, 3
      {1, 1, 1}};                                                          // interior
  EXPECT_EQ(vtk_tetrahedron_lattice(4), vtk);
  expect_vtk_coordinates(CellType::Tetrahedron, 4, lattice_table(vtk, 4));
}

// A second derivation of VTK's Lagrange tetrahedron order, for every order up to 10,
// straight from VTK's 4-component barycentric tables (vtkHigherOrderTetra.cxx) instead
// of the face vertex triples the library derived from them. Barycentric index
// b = (x, y, z, rest); vertex v maximises b[VertexMaxCoords[v]]; a triangle's vertex k
// maximises its b[(k+2)%3] (vtkHigherOrderTriangle.cxx).
void vtk_triangle_bary(int q, int m, std::vector<std::array<int, 3>>& out) {
  if (q < 0) return;
  if (q == 0) return out.push_back({m, m, m});
  auto point = [&](int a, int wa, int b, int wb) {  // weight wa on index a, wb on b
    std::array<int, 3> x{m, m, m};
    x[a] += wa, x[b] += wb;
    out.push_back(x);
  };
  for (int k = 0; k < 3; ++k) point((k + 2) % 3, q, k, 0);
  for (int k = 0; k < 3; ++k)  // edge k runs from vertex k (index k+2) to vertex k+1 (index k)
    for (int i = 1; i < q; ++i) point((k + 2) % 3, q - i, k, i);
  vtk_triangle_bary(q - 3, m + 1, out);
}
void vtk_tetra_bary(int q, int m, std::vector<std::array<int, 4>>& out) {
  const int vertex_max[4] = {3, 0, 1, 2};
  const int edges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  const int face_b[4][3] = {{0, 2, 3}, {2, 0, 1}, {2, 1, 3}, {1, 0, 3}};
  const int face_min[4] = {1, 3, 0, 2};
  if (q < 0) return;
  if (q == 0) return out.push_back({m, m, m, m});
  auto point = [&](int a, int wa, int b, int wb) {
    std::array<int, 4> x{m, m, m, m};
    x[vertex_max[a]] += wa, x[vertex_max[b]] += wb;
    out.push_back(x);
  };
  for (int v = 0; v < 4; ++v) point(v, q, v, 0);
  for (const auto& e : edges)
    for (int i = 1; i < q; ++i) point(e[0], q - i, e[1], i);
  std::vector<std::array<int, 3>> tri;
  vtk_triangle_bary(q - 3, 0, tri);
  for (int f = 0; f < 4; ++f)
    for (const auto& t : tri) {
      std::array<int, 4> b{};
      for (int i = 0; i < 3; ++i) b[face_b[f][i]] = m + 1 + t[i];
      b[face_min[f]] = m;
      out.push_back(b);
    }
  vtk_tetra_bary(q - 4, m + 1, out);
}

TEST(VtuPermutation, LagrangeTetraAgreesWithVtkBarycentricTables) {
  for (int p = 1; p <= 10; ++p) {
    std::vector<std::array<int, 4>> bary;
    vtk_tetra_bary(p, 0, bary);
    const auto lattice = vtk_tetrahedron_lattice(p);
    ASSERT_EQ(bary.size(), lattice.size()) << "order " << p;
    for (size_t k = 0; k < bary.size(); ++k) {
      EXPECT_EQ(bary[k][0] + bary[k][1] + bary[k][2] + bary[k][3], p);
      EXPECT_EQ((std::array<int, 3>{bary[k][0], bary[k][1], bary[k][2]}), lattice[k]) << "order " << p << " point " << k;
    }
  }
}

// ---- A minimal XML reader: elements, attributes, text; enough for our own files ----
struct Xml {
  std::string tag, text;
  std::map<std::string, std::string> attr;
  std::vector<Xml> children;
  std::vector<const Xml*> all(const std::string& t) const {
    std::vector<const Xml*> r;
    for (const auto& c : children) if (c.tag == t) r.push_back(&c);
    return r;
  }
  const Xml& child(const std::string& t) const {
    const auto r = all(t);
    if (r.size() != 1) throw std::runtime_error("expected one <" + t + "> in <" + tag + ">");
    return *r[0];
  }
  const Xml& array(const std::string& name) const {  // the DataArray called `name`
    for (const auto* c : all("DataArray"))
      if (c->attr.at("Name") == name) return *c;
    throw std::runtime_error("no DataArray " + name);
  }
  std::vector<double> numbers() const {  // strtod: correctly rounded, like VTK's reader
    std::vector<double> v;
    char* end = nullptr;
    for (const char* p = text.c_str();; p = end) {
      const double x = std::strtod(p, &end);
      if (end == p) return v;
      v.push_back(x);
    }
  }
};

std::string unescape(std::string s) {  // "&amp;" last, so "&amp;lt;" stays "&lt;"
  const std::pair<std::string, std::string> entities[] = {
      {"&lt;", "<"}, {"&gt;", ">"}, {"&quot;", "\""}, {"&apos;", "'"}, {"&amp;", "&"}};
  for (const auto& [e, c] : entities)
    for (size_t p = 0; (p = s.find(e, p)) != std::string::npos; ++p) s.replace(p, e.size(), c);
  return s;
}

struct XmlParser {
  std::string s;
  size_t i = 0;
  void skip_space() { while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i; }
  std::string name() {
    const size_t b = i;
    while (i < s.size() && (std::isalnum(static_cast<unsigned char>(s[i])) || s[i] == '_')) ++i;
    return s.substr(b, i - b);
  }
  void expect(char c) {
    if (i >= s.size() || s[i++] != c) throw std::runtime_error(std::string("XML: expected ") + c);
  }
  Xml element() {
    Xml x;
    expect('<');
    x.tag = name();
    for (skip_space(); s[i] != '>' && s[i] != '/'; skip_space()) {
      const std::string key = name();
      expect('=');
      expect('"');
      const size_t end = s.find('"', i);
      x.attr[key] = unescape(s.substr(i, end - i));
      i = end + 1;
    }
    if (s[i] == '/') ++i;
    expect('>');
    if (s[i - 2] == '/') return x;
    while (true) {
      const size_t lt = s.find('<', i);
      x.text += unescape(s.substr(i, lt - i));
      i = lt;
      if (s.compare(i, 2, "</") == 0) break;
      x.children.push_back(element());
    }
    i += 2;
    if (name() != x.tag) throw std::runtime_error("XML: mismatched </" + x.tag + ">");
    expect('>');
    return x;
  }
};

Xml read_xml(const std::filesystem::path& path) {
  std::ifstream in(path);
  XmlParser p{std::string(std::istreambuf_iterator<char>(in), {})};
  if (p.s.compare(0, 5, "<?xml") != 0) throw std::runtime_error("no XML declaration");
  p.i = p.s.find("?>") + 2;
  p.skip_space();
  Xml root = p.element();
  p.skip_space();
  if (p.i != p.s.size()) throw std::runtime_error("trailing content after root element");
  return root;
}

// DataArray `a` holds exactly `values`, tuple by tuple (a column is a VTK tuple).
void expect_array(const Xml& a, const Eigen::MatrixXd& values) {
  EXPECT_EQ(a.attr.at("type"), "Float64");
  EXPECT_EQ(a.attr.at("NumberOfComponents"), std::to_string(values.rows()));
  const auto v = a.numbers();
  ASSERT_EQ(v.size(), size_t(values.size()));
  for (Eigen::Index i = 0; i < values.size(); ++i)
    EXPECT_TRUE(v[i] == values.data()[i] && std::signbit(v[i]) == std::signbit(values.data()[i]))
        << a.attr.at("Name") << " entry " << i << ": " << v[i] << " vs " << values.data()[i];
}

// A scratch directory per test, removed afterwards.
class VtuFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("hofem_vtu_" + std::to_string(::getpid()) + "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

// `copies` reference elements, copy c shifted by (3c, 0, 0); node ids of copy c are
// numbered backwards so that connectivity is not simply 0, 1, 2, ...
Mesh reference_mesh(CellType cell, int order, int copies) {
  const Eigen::MatrixXd x = cell == CellType::Hexahedron ? hex_nodes(order) : simplex_lagrange_nodes(cell, order);
  const int n = static_cast<int>(x.cols());
  Mesh m;
  m.cell = cell;
  m.order = order;
  m.nodes.resize(3, n * copies);
  m.elements.resize(n, copies);
  for (int c = 0; c < copies; ++c)
    for (int k = 0; k < n; ++k) {
      const int id = c * n + (c % 2 == 1 ? n - 1 - k : k);
      m.nodes.col(id) = x.col(k) + Eigen::Vector3d(3.0 * c, 0, 0);
      m.elements(k, c) = id;
    }
  return m;
}

TEST_F(VtuFiles, EveryCellKindReadsBackWithCountsTypesOffsetsAndFields) {
  const std::vector<std::pair<CellType, int>> cells{{CellType::Tetrahedron, 1}, {CellType::Tetrahedron, 2},
                                                    {CellType::Tetrahedron, 3}, {CellType::Tetrahedron, 5},
                                                    {CellType::Hexahedron, 1},  {CellType::Hexahedron, 2}};
  for (const auto& [cell, order] : cells) {
    SCOPED_TRACE(std::string(name(cell)) + " order " + std::to_string(order));
    const Mesh m = reference_mesh(cell, order, 3);
    const int npe = m.nodes_per_element();
    VtuField u{"displacement", Eigen::MatrixXd::Random(3, m.num_nodes()) / 3.0};
    VtuField stress{"stress", Eigen::MatrixXd::Random(9, m.num_elements()) * 1e5};
    VtuField id{"element id", Eigen::RowVectorXd::LinSpaced(m.num_elements(), 0, m.num_elements() - 1)};
    const auto path = dir_ / "mesh.vtu";
    write_vtu(path.string(), m, {u}, {stress, id});

    const Xml root = read_xml(path);
    EXPECT_EQ(root.tag, "VTKFile");
    EXPECT_EQ(root.attr.at("type"), "UnstructuredGrid");
    const Xml& piece = root.child("UnstructuredGrid").child("Piece");
    EXPECT_EQ(piece.attr.at("NumberOfPoints"), std::to_string(m.num_nodes()));
    EXPECT_EQ(piece.attr.at("NumberOfCells"), "3");
    const Xml& cells_xml = piece.child("Cells");
    const auto conn = cells_xml.array("connectivity").numbers();
    EXPECT_EQ(cells_xml.array("types").attr.at("type"), "UInt8");
    EXPECT_EQ(cells_xml.array("types").numbers(), std::vector<double>(3, vtk_cell_type(cell, order)));
    EXPECT_EQ(cells_xml.array("offsets").numbers(), (std::vector<double>{1.0 * npe, 2.0 * npe, 3.0 * npe}));
    ASSERT_EQ(conn.size(), size_t(3 * npe));
    const auto perm = gmsh_to_vtk_permutation(cell, order);
    for (int e = 0; e < 3; ++e)
      for (int k = 0; k < npe; ++k) EXPECT_EQ(conn[e * npe + k], m.elements(perm[k], e));

    expect_array(piece.child("Points").child("DataArray"), m.nodes);
    expect_array(piece.child("PointData").array("displacement"), u.values);
    expect_array(piece.child("CellData").array("stress"), stress.values);
    expect_array(piece.child("CellData").array("element id"), id.values);
  }
}

TEST_F(VtuFiles, DoublesAndOddFieldNamesRoundTripExactly) {
  Mesh m = reference_mesh(CellType::Tetrahedron, 1, 1);
  m.nodes(0, 1) = 0.1;
  m.nodes(1, 2) = 1.0 / 3.0;
  m.nodes(2, 3) = std::nextafter(1.0, 2.0);
  Eigen::MatrixXd s(1, 4);
  s << -2.5e300, 1e-300, std::numbers::pi, -0.0;
  write_vtu((dir_ / "a.vtu").string(), m, {{"p<&>\"'q", s}}, {});
  const Xml piece = read_xml(dir_ / "a.vtu").child("UnstructuredGrid").child("Piece");
  expect_array(piece.child("PointData").array("p<&>\"'q"), s);
  expect_array(piece.child("Points").child("DataArray"), m.nodes);
}

// The message must name the offending thing; returns it for further checks.
template <typename E, typename F>
std::string error_of(F&& f) {
  try { f(); } catch (const E& e) { return e.what(); }
  ADD_FAILURE() << "no exception of the expected type";
  return {};
}

TEST_F(VtuFiles, WrongFieldSizesNameTheFieldAndWriteNothing) {
  const Mesh m = reference_mesh(CellType::Tetrahedron, 2, 2);
  const auto path = (dir_ / "bad.vtu").string();
  std::string msg = error_of<std::invalid_argument>(
      [&] { write_vtu(path, m, {{"velocity", Eigen::MatrixXd::Zero(3, m.num_nodes() - 1)}}, {}); });
  EXPECT_NE(msg.find("velocity"), std::string::npos) << msg;
  msg = error_of<std::invalid_argument>([&] { write_vtu(path, m, {}, {{"J", Eigen::MatrixXd::Zero(1, 3)}}); });
  EXPECT_NE(msg.find("'J'"), std::string::npos) << msg;
  Eigen::MatrixXd bad = Eigen::MatrixXd::Zero(1, m.num_nodes());
  bad(0, 5) = std::numeric_limits<double>::quiet_NaN();
  msg = error_of<std::invalid_argument>([&] { write_vtu(path, m, {{"energy", bad}}, {}); });
  EXPECT_NE(msg.find("energy"), std::string::npos) << msg;
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST_F(VtuFiles, UnwritablePathsNameThePath) {
  const Mesh m = reference_mesh(CellType::Hexahedron, 1, 1);
  const std::string missing = (dir_ / "no_such_dir" / "out.vtu").string();
  std::string msg = error_of<std::runtime_error>([&] { write_vtu(missing, m, {}, {}); });
  EXPECT_NE(msg.find(missing), std::string::npos) << msg;
  msg = error_of<std::runtime_error>([&] { write_vtu(dir_.string(), m, {}, {}); });  // a directory
  EXPECT_NE(msg.find(dir_.string()), std::string::npos) << msg;
  msg = error_of<std::runtime_error>([&] { write_pvd(missing + ".pvd", {{0.0, "a.vtu"}}); });
  EXPECT_NE(msg.find(missing + ".pvd"), std::string::npos) << msg;
}

TEST_F(VtuFiles, PvdListsFramesInOrder) {
  const std::vector<std::pair<double, std::string>> frames{
      {0.0, "frame_0000.vtu"}, {0.1, "frame_0001.vtu"}, {1.0 / 3.0, "sub dir/frame&2.vtu"}, {2.5e-7, "x.vtu"}};
  write_pvd((dir_ / "series.pvd").string(), frames);
  const Xml root = read_xml(dir_ / "series.pvd");
  EXPECT_EQ(root.attr.at("type"), "Collection");
  const auto sets = root.child("Collection").all("DataSet");
  ASSERT_EQ(sets.size(), frames.size());
  for (size_t i = 0; i < frames.size(); ++i) {
    EXPECT_EQ(std::strtod(sets[i]->attr.at("timestep").c_str(), nullptr), frames[i].first);
    EXPECT_EQ(sets[i]->attr.at("file"), frames[i].second);
  }
  EXPECT_THROW(write_pvd((dir_ / "nan.pvd").string(), {{std::nan(""), "a.vtu"}}), std::invalid_argument);
}

}  // namespace
}  // namespace hofem
