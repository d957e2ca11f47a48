#pragma once
// ParaView output: VTK XML UnstructuredGrid (.vtu: ASCII, or binary appended data,
// raw or zlib-compressed; core/io/vtu_appended.hpp) and .pvd time series.
//
// hofem stores element nodes in Gmsh order (core/basis/lagrange_nodes.hpp); VTK
// numbers the same nodes differently. gmsh_to_vtk_permutation() gives, for each
// cell kind, perm with vtk_node[k] = gmsh_node[perm[k]]. It is computed by
// generating VTK's points as integer lattice coordinates and matching them against
// hofem's Gmsh-ordered nodes, so no node table is typed in by hand.
//
// VTK orderings used, and where they come from (Kitware/VTK, Common/DataModel/):
//  * VTK_TETRA (10): vertices (0,0,0), (1,0,0), (0,1,0), (0,0,1): vtkTetra, the same
//    as Gmsh's Tet4 vertex order, so the permutation is the identity.
//  * VTK_QUADRATIC_TETRA (24): vtkQuadraticTetra.h: "point ids 4-9 are the midedge
//    nodes between (0,1), (1,2), (2,0), (0,3), (1,3), and (2,3)" (parametric
//    coordinates in vtkQuadraticTetra.cxx, vtkQTetraCellPCoords). Gmsh's edges are
//    0-1, 1-2, 2-0, 3-0, 3-2, 3-1, so Tet10 differs by swapping Gmsh nodes 8 and 9.
//  * VTK_HEXAHEDRON (12): vtkHexahedron.cxx, vtkHexahedronCellPCoords: (0,0,0),
//    (1,0,0), (1,1,0), (0,1,0), then the same at z = 1: Gmsh's Hex8 order.
//  * VTK_QUADRATIC_HEXAHEDRON (25): vtkQuadraticHexahedron.h: midedge nodes 8-19 on
//    edges (0,1), (1,2), (2,3), (3,0), (4,5), (5,6), (6,7), (7,4), (0,4), (1,5),
//    (2,6), (3,7) (vtkQHexCellPCoords agrees). Gmsh's edge order differs (see
//    hex_nodes), so Hex20 needs the permutation 0-7, 8 11 13 9 16 18 19 17 10 12 14 15.
//  * VTK_LAGRANGE_TETRAHEDRON (71), any order p (used for p >= 3):
//    vtkHigherOrderTetra.cxx (BarycentricIndex, EdgeVertices, FaceBCoords,
//    FaceMinCoord, VertexMaxCoords), vtkHigherOrderTriangle.cxx (BarycentricIndex),
//    and Kitware's blog "Modeling arbitrary-order Lagrange finite elements in the
//    Visualization Toolkit" (Corona & Thompson, 2018: vertices, then edge points,
//    then face points, then the interior, simplices "peeled like an onion"):
//      1. vertices as vtkTetra;
//      2. p-1 points per edge, edges 0->1, 1->2, 2->0, 0->3, 1->3, 2->3, each run
//         from its first vertex to its second;
//      3. faces, as triangles (a, b, c) of tet vertices: (0,1,3), (2,3,1), (0,3,2),
//         (0,2,1) (derived from FaceBCoords/FaceMinCoord and the triangle's vertex
//         convention); each face's interior is the order p-3 triangle, in VTK
//         triangle order (vertices, edges a->b, b->c, c->a, interior recursively),
//         placed at a + ((s+1)(b-a) + (t+1)(c-a))/p;
//      4. the interior: the order p-4 tetrahedron, recursively, shifted by (1,1,1)/p.
//    The files written here are VTK XML version 0.1; VTK's 2.2 ordering change
//    concerns Lagrange hexahedra only, not tetrahedra. VTK 8.x compiled Lagrange
//    tetrahedra up to order 6 (VTK_LAGRANGE_TETRAHEDRON_MAX_ORDER); VTK 9 has no
//    such limit.
//
// File format: VTK "VTK File Formats" (XML UnstructuredGrid; Cells hold
// "connectivity", "offsets" = end offset of each cell, "types"), as read by
// vtkXMLUnstructuredDataReader.cxx ("The file format skips the first 0 in the
// offsets array").
#include "mesh/mesh.hpp"

#include <Eigen/Core>

#include <array>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace hofem {

/// A named field to write: components x count. Point fields have one column per
/// mesh node, cell fields one per element. 1 component = scalar, 3 = vector (e.g.
/// "displacement", for ParaView's Warp By Vector), 9 = tensor (row-major 3x3).
struct VtuField {
  std::string name;
  Eigen::MatrixXd values;
};

/// How write_vtu stores the arrays. ascii: inline text, 17 significant digits
/// (readable, ~2.5x larger, slow); binary: one <AppendedData encoding="raw"> block,
/// each array its bytes as in memory; zlib: the same, compressed in the
/// vtkZLibDataCompressor block layout (vtu_appended.hpp has both layouts).
enum class VtuFormat { ascii, binary, zlib };

/// "ascii" | "binary" | "zlib" -> VtuFormat; std::invalid_argument naming the text otherwise.
VtuFormat parse_vtu_format(std::string_view text);
std::string_view to_string(VtuFormat format);

/// VTK cell type code for a hofem cell: Tet order 1/2/>=3 -> 10/24/71, Hex8 -> 12,
/// Hex20 -> 25. Throws std::invalid_argument for anything else.
int vtk_cell_type(CellType cell, int order);

/// VTK's Lagrange tetrahedron points of order p, in VTK's point order, as integer
/// lattice coordinates (x, y, z) in units of 1/p (the header comment gives the rule).
std::vector<std::array<int, 3>> vtk_tetrahedron_lattice(int p);

/// perm with vtk_node[k] = gmsh_node[perm[k]] for the cell written by vtk_cell_type.
/// Throws std::invalid_argument for unsupported cells or orders.
std::vector<int> gmsh_to_vtk_permutation(CellType cell, int order);

/// Writes `mesh` as a .vtu file in `format`: reference coordinates as Points (write the
/// displacement as a point field; ParaView's Warp By Vector deforms it), cells in VTK
/// node order, then the point and cell fields. Doubles are written with 17
/// significant digits in ASCII (and bit for bit in the binary formats), so they read
/// back exactly.
/// Throws std::invalid_argument naming the field if a field has the wrong number of
/// columns, no components, an empty or duplicate name, or a non-finite value (VTK's
/// ASCII reader cannot parse "nan"/"inf"); std::invalid_argument if the mesh is
/// inconsistent (element rows, node ids); std::runtime_error naming `path` if the
/// file cannot be written. Fields are checked before the file is opened.
void write_vtu(const std::string& path, const Mesh& mesh, const std::vector<VtuField>& point_fields,
               const std::vector<VtuField>& cell_fields, VtuFormat format = VtuFormat::ascii);

/// Writes a .pvd collection listing (time, .vtu file name relative to the .pvd)
/// frames in the order given. Throws std::invalid_argument for a non-finite time or
/// an empty file name, std::runtime_error naming `path` if it cannot be written.
void write_pvd(const std::string& path, const std::vector<std::pair<double, std::string>>& frames);

}  // namespace hofem
