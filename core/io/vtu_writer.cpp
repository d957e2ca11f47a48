#include "io/vtu_writer.hpp"

#include "io/atomic_file.hpp"
#include "io/vtu_appended.hpp"

#include "basis/lagrange_nodes.hpp"
#include "basis/element_orders.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iterator>
#include <map>
#include <set>
#include <stdexcept>
#include <string_view>

namespace hofem {

namespace detail {

std::string xml_escape(std::string_view s) {
  std::string r;
  for (const char c : s) {
    switch (c) {
      case '&': r += "&amp;"; break;
      case '<': r += "&lt;"; break;
      case '>': r += "&gt;"; break;
      case '"': r += "&quot;"; break;
      case '\'': r += "&apos;"; break;
      default: r += c;
    }
  }
  return r;
}

}  // namespace detail

namespace {

using detail::xml_escape;

// VTK cell type codes (Common/DataModel/vtkCellType.h).
constexpr int kVtkTetra = 10;
constexpr int kVtkHexahedron = 12;
constexpr int kVtkQuadraticTetra = 24;
constexpr int kVtkQuadraticHexahedron = 25;
constexpr int kVtkLagrangeTetrahedron = 71;

using Point3 = std::array<int, 3>;

// VTK's triangle point order (vtkHigherOrderTriangle::BarycentricIndex): vertices
// (0,0), (p,0), (0,p); p-1 points on each edge 0->1, 1->2, 2->0; then the order p-3
// triangle, recursively, shifted one lattice step inwards.
void append_vtk_triangle(int p, int shift, std::vector<std::array<int, 2>>& out) {
  if (p < 0) return;
  if (p == 0) {
    out.push_back({shift, shift});
    return;
  }
  const std::array<std::array<int, 2>, 3> v{{{0, 0}, {p, 0}, {0, p}}};
  for (const auto& x : v) out.push_back({x[0] + shift, x[1] + shift});
  for (int e = 0; e < 3; ++e) {
    const auto& a = v[e];
    const auto& b = v[(e + 1) % 3];
    for (int i = 1; i < p; ++i)
      out.push_back({shift + a[0] + i * (b[0] - a[0]) / p, shift + a[1] + i * (b[1] - a[1]) / p});
  }
  append_vtk_triangle(p - 3, shift + 1, out);
}

// VTK's tetrahedron point order, recursively: the rule in vtu_writer.hpp.
void append_vtk_tetrahedron(int p, int shift, std::vector<Point3>& out) {
  if (p < 0) return;
  if (p == 0) {
    out.push_back({shift, shift, shift});
    return;
  }
  const std::array<Point3, 4> v{{{0, 0, 0}, {p, 0, 0}, {0, p, 0}, {0, 0, p}}};
  auto at = [&](const Point3& x) { return Point3{x[0] + shift, x[1] + shift, x[2] + shift}; };
  for (const auto& x : v) out.push_back(at(x));
  // vtkHigherOrderTetra EdgeVertices: each edge runs from its first vertex to its second.
  const int edges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  for (const auto& e : edges)
    for (int i = 1; i < p; ++i) {
      Point3 x{};
      for (int c = 0; c < 3; ++c) x[c] = v[e[0]][c] + i * (v[e[1]][c] - v[e[0]][c]) / p;
      out.push_back(at(x));
    }
  // Face f's triangle vertex k is the tet vertex whose barycentric index is
  // FaceBCoords[f][(k+2)%3] (the triangle's vertex k maximises its own barycentric
  // index (k+2)%3; tet index 3 belongs to vertex 0, index i < 3 to vertex i+1).
  const int faces[4][3] = {{0, 1, 3}, {2, 3, 1}, {0, 3, 2}, {0, 2, 1}};
  std::vector<std::array<int, 2>> face_points;
  append_vtk_triangle(p - 3, 0, face_points);
  for (const auto& f : faces)
    for (const auto& st : face_points) {
      Point3 x{};
      for (int c = 0; c < 3; ++c)
        x[c] = v[f[0]][c] + ((st[0] + 1) * (v[f[1]][c] - v[f[0]][c]) + (st[1] + 1) * (v[f[2]][c] - v[f[0]][c])) / p;
      out.push_back(at(x));
    }
  append_vtk_tetrahedron(p - 4, shift + 1, out);
}

// perm[k] = index in `gmsh` of vtk[k]; both must hold the same points exactly once.
std::vector<int> match_points(const std::vector<Point3>& vtk, const std::vector<Point3>& gmsh, std::string_view what) {
  std::map<Point3, int> index;
  for (size_t i = 0; i < gmsh.size(); ++i) index.emplace(gmsh[i], static_cast<int>(i));
  if (index.size() != gmsh.size() || vtk.size() != gmsh.size())
    throw std::logic_error(fmt::format("{}: Gmsh and VTK node sets differ in size", what));
  std::vector<int> perm;
  std::vector<bool> used(gmsh.size(), false);
  for (const auto& x : vtk) {
    const auto it = index.find(x);
    if (it == index.end() || used[it->second])
      throw std::logic_error(fmt::format("{}: VTK point ({},{},{}) has no unique Gmsh node", what, x[0], x[1], x[2]));
    used[it->second] = true;
    perm.push_back(it->second);
  }
  return perm;
}

std::vector<int> hex_permutation(int order) {
  // vtkHexahedronCellPCoords mapped from [0,1]^3 to hofem's [-1,1]^3.
  const std::array<Point3, 8> v{{{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                 {-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}}};
  std::vector<Point3> vtk(v.begin(), v.end());
  if (order == 2) {
    // vtkQuadraticHexahedron.h edge order.
    const int edges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                              {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
    for (const auto& e : edges)
      vtk.push_back({(v[e[0]][0] + v[e[1]][0]) / 2, (v[e[0]][1] + v[e[1]][1]) / 2, (v[e[0]][2] + v[e[1]][2]) / 2});
  }
  const Eigen::MatrixXd x = hex_nodes(order);  // Gmsh order, coordinates in {-1, 0, 1}
  std::vector<Point3> gmsh;
  for (Eigen::Index n = 0; n < x.cols(); ++n)
    gmsh.push_back({static_cast<int>(std::lround(x(0, n))), static_cast<int>(std::lround(x(1, n))),
                    static_cast<int>(std::lround(x(2, n)))});
  return match_points(vtk, gmsh, order == 1 ? "Hex8" : "Hex20");
}

// Buffered output to a file; every failure becomes a std::runtime_error naming the path.
// Text output in 1 MB chunks through an AtomicFile: a frame is complete under
// its name or not there at all.
class XmlFile {
 public:
  explicit XmlFile(const std::string& path) : file_(path) {}
  template <typename... Args>
  void print(fmt::format_string<Args...> f, Args&&... args) {
    fmt::format_to(std::back_inserter(buf_), f, std::forward<Args>(args)...);
    if (buf_.size() > (1u << 20)) flush();
  }
  void flush() {
    file_.write(std::string_view(buf_.data(), buf_.size()));
    buf_.clear();
  }
  void close() {
    flush();
    file_.commit();
  }

 private:
  AtomicFile file_;
  fmt::memory_buffer buf_;
};

void check_fields(const std::vector<VtuField>& fields, Eigen::Index count, std::string_view kind,
                  std::string_view per) {
  std::set<std::string> names;
  for (const auto& f : fields) {
    if (f.name.empty()) throw std::invalid_argument(fmt::format("{} field with an empty name", kind));
    if (!names.insert(f.name).second)
      throw std::invalid_argument(fmt::format("{} field '{}' given twice", kind, f.name));
    if (f.values.cols() != count)
      throw std::invalid_argument(fmt::format("{} field '{}' has {} columns, expected {} (one per {})", kind, f.name,
                                              f.values.cols(), count, per));
    if (f.values.rows() < 1) throw std::invalid_argument(fmt::format("{} field '{}' has no components", kind, f.name));
    for (Eigen::Index j = 0; j < f.values.cols(); ++j)
      for (Eigen::Index i = 0; i < f.values.rows(); ++i)
        if (!std::isfinite(f.values(i, j)))
          throw std::invalid_argument(fmt::format("{} field '{}' has a non-finite value ({}) at component {}, {} {}",
                                                  kind, f.name, f.values(i, j), i, per, j));
  }
}

// One Float64 DataArray, one tuple (column) per line.
void write_doubles(XmlFile& out, std::string_view name, const Eigen::Ref<const Eigen::MatrixXd>& values, int indent) {
  out.print("{:{}}<DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"ascii\">\n", "", indent,
            xml_escape(name), values.rows());
  for (Eigen::Index j = 0; j < values.cols(); ++j) {
    out.print("{:{}}", "", indent + 2);
    out.print("{:.17g}", values(0, j));
    for (Eigen::Index i = 1; i < values.rows(); ++i) out.print(" {:.17g}", values(i, j));
    out.print("\n");
  }
  out.print("{:{}}</DataArray>\n", "", indent);
}

// Separator before entry e of a list printed `per_line` entries to a line.
std::string_view line_start(Eigen::Index e, int per_line) {
  if (e == 0) return "          ";
  return e % per_line == 0 ? "\n          " : " ";
}

void write_field_block(XmlFile& out, std::string_view tag, const std::vector<VtuField>& fields) {
  out.print("      <{}>\n", tag);
  for (const auto& f : fields) write_doubles(out, f.name, f.values, 8);
  out.print("      </{}>\n", tag);
}

}  // namespace

VtuFormat parse_vtu_format(std::string_view text) {
  if (text == "ascii") return VtuFormat::ascii;
  if (text == "binary") return VtuFormat::binary;
  if (text == "zlib") return VtuFormat::zlib;
  throw std::invalid_argument(fmt::format("unknown .vtu format '{}' (expected ascii, binary or zlib)", text));
}

std::string_view to_string(VtuFormat format) {
  switch (format) {
    case VtuFormat::ascii: return "ascii";
    case VtuFormat::binary: return "binary";
    case VtuFormat::zlib: return "zlib";
  }
  return "?";
}

int vtk_cell_type(CellType cell, int order) {
  // Linear triangles: embedded surfaces (finite cell output); VTK_TRIANGLE = 5,
  // vertices in Gmsh's order (vtkTriangle).
  if (cell == CellType::Triangle && order == 1) return 5;
  if (cell == CellType::Tetrahedron && order >= 1)
    return order == 1 ? kVtkTetra : order == 2 ? kVtkQuadraticTetra : kVtkLagrangeTetrahedron;
  if (cell == CellType::Hexahedron && supports_order(cell, order))
    return order == 1 ? kVtkHexahedron : kVtkQuadraticHexahedron;
  throw std::invalid_argument(fmt::format("no VTK cell for {} of order {} (tet: {}; hex: {}; triangle: order 1)",
                                          name(cell), order, supported_orders(CellType::Tetrahedron),
                                          supported_orders(CellType::Hexahedron)));
}

std::vector<std::array<int, 3>> vtk_tetrahedron_lattice(int p) {
  if (p < 1) throw std::invalid_argument(fmt::format("Lagrange tetrahedron order must be >= 1, got {}", p));
  std::vector<Point3> out;
  append_vtk_tetrahedron(p, 0, out);
  return out;
}

std::vector<int> gmsh_to_vtk_permutation(CellType cell, int order) {
  vtk_cell_type(cell, order);  // validates
  if (cell == CellType::Triangle) return {0, 1, 2};
  if (cell == CellType::Hexahedron) return hex_permutation(order);
  // VTK_TETRA and VTK_QUADRATIC_TETRA number their points as the Lagrange
  // tetrahedron of order 1 and 2 does (vtkTetra, vtkQuadraticTetra.h), so one rule serves.
  return match_points(vtk_tetrahedron_lattice(order), tetrahedron_lattice(order), "tetrahedron");
}

void write_vtu(const std::string& path, const Mesh& mesh, const std::vector<VtuField>& point_fields,
               const std::vector<VtuField>& cell_fields, VtuFormat format) {
  const int type = vtk_cell_type(mesh.cell, mesh.order);
  const int npe = nodes_per_element(mesh.cell, mesh.order);
  if (mesh.nodes_per_element() != npe)
    throw std::invalid_argument(fmt::format("mesh elements have {} rows, a {} of order {} has {} nodes",
                                            mesh.nodes_per_element(), name(mesh.cell), mesh.order, npe));
  const Eigen::Index num_nodes = mesh.nodes.cols();
  for (Eigen::Index e = 0; e < mesh.elements.cols(); ++e)
    for (Eigen::Index k = 0; k < mesh.elements.rows(); ++k)
      if (mesh.elements(k, e) < 0 || mesh.elements(k, e) >= num_nodes)
        throw std::invalid_argument(fmt::format("element {} refers to node {}, mesh has {} nodes", e,
                                                mesh.elements(k, e), num_nodes));
  if (!mesh.nodes.allFinite()) throw std::invalid_argument("mesh node coordinates are not all finite");
  check_fields(point_fields, num_nodes, "point", "node");
  check_fields(cell_fields, mesh.elements.cols(), "cell", "element");
  const std::vector<int> perm = gmsh_to_vtk_permutation(mesh.cell, mesh.order);
  if (format != VtuFormat::ascii) {
    detail::write_vtu_appended(path, mesh, perm, type, point_fields, cell_fields, format == VtuFormat::zlib);
    return;
  }

  XmlFile out(path);
  out.print("<?xml version=\"1.0\"?>\n");
  out.print("<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n");
  out.print("  <UnstructuredGrid>\n");
  out.print("    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", num_nodes, mesh.elements.cols());
  write_field_block(out, "PointData", point_fields);
  write_field_block(out, "CellData", cell_fields);
  out.print("      <Points>\n");
  write_doubles(out, "Points", mesh.nodes, 8);
  out.print("      </Points>\n");
  out.print("      <Cells>\n");
  out.print("        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
  for (Eigen::Index e = 0; e < mesh.elements.cols(); ++e) {
    out.print("          {}", mesh.elements(perm[0], e));
    for (int k = 1; k < npe; ++k) out.print(" {}", mesh.elements(perm[k], e));
    out.print("\n");
  }
  out.print("        </DataArray>\n");
  // End offset of each cell into connectivity (VTK omits the leading 0).
  out.print("        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
  for (Eigen::Index e = 0; e < mesh.elements.cols(); ++e)
    out.print("{}{}", line_start(e, 16), (e + 1) * static_cast<long long>(npe));
  if (mesh.elements.cols() > 0) out.print("\n");
  out.print("        </DataArray>\n");
  out.print("        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
  for (Eigen::Index e = 0; e < mesh.elements.cols(); ++e) out.print("{}{}", line_start(e, 32), type);
  if (mesh.elements.cols() > 0) out.print("\n");
  out.print("        </DataArray>\n");
  out.print("      </Cells>\n");
  out.print("    </Piece>\n");
  out.print("  </UnstructuredGrid>\n");
  out.print("</VTKFile>\n");
  out.close();
}

void write_pvd(const std::string& path, const std::vector<std::pair<double, std::string>>& frames) {
  for (const auto& [time, file] : frames) {
    if (!std::isfinite(time))
      throw std::invalid_argument(fmt::format("pvd frame '{}' has a non-finite time {}", file, time));
    if (file.empty()) throw std::invalid_argument(fmt::format("pvd frame at time {} has no file name", time));
  }
  XmlFile out(path);
  out.print("<?xml version=\"1.0\"?>\n");
  out.print("<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n");
  out.print("  <Collection>\n");
  for (const auto& [time, file] : frames)
    out.print("    <DataSet timestep=\"{:.17g}\" group=\"\" part=\"0\" file=\"{}\"/>\n", time, xml_escape(file));
  out.print("  </Collection>\n");
  out.print("</VTKFile>\n");
  out.close();
}

}  // namespace hofem
