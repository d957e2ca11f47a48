#pragma once
// An unstructured mesh of one element type: tetrahedra of any Lagrange order
// (Tet4, Tet10, Tet20, ...) or hexahedra (Hex8, Hex20), nodes in reference
// (undeformed) coordinates, connectivity in Gmsh node order (core/basis).
#include "quadrature/cell_type.hpp"

#include <Eigen/Core>

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace hofem {

/// Malformed or unusable mesh input; the message names the file / line or element.
class MeshError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Where a mesh read from a file came from, so that errors about its elements
/// name the file, the element's own tag and its line (not only hofem's index).
struct MeshSource {
  std::string file;                     ///< empty for generated meshes
  std::vector<long long> element_tags;  ///< per element: its tag in the file
  std::vector<int> element_lines;       ///< per element: its line in the file
};

struct Mesh {
  CellType cell = CellType::Tetrahedron;  ///< Tetrahedron or Hexahedron
  int order = 1;                          ///< Lagrange order (hex: 1 = Hex8, 2 = Hex20 serendipity)
  Eigen::Matrix3Xd nodes;                 ///< 3 x num_nodes reference coordinates
  /// nodes_per_element x num_elements, column e = node ids of element e in Gmsh order.
  Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic> elements;
  /// Named node sets: physical groups of a .msh file, or sets made by a generator
  /// ("boundary", "xmin", "xmax", ...). Each sorted, without duplicates.
  std::map<std::string, std::vector<int>> node_sets;
  /// Named element sets (physical volume groups).
  std::map<std::string, std::vector<int>> element_sets;
  MeshSource source;  ///< file, element tags and lines (empty for generated meshes)

  int num_nodes() const { return static_cast<int>(nodes.cols()); }
  int num_elements() const { return static_cast<int>(elements.cols()); }
  int nodes_per_element() const { return static_cast<int>(elements.rows()); }
  /// Number of vertex (corner) nodes per element: 4 or 8.
  int vertices_per_element() const { return cell == CellType::Tetrahedron ? 4 : 8; }

  /// Node set by name; throws MeshError naming the set and the available ones.
  const std::vector<int>& node_set(const std::string& name) const;
};

/// "ball.msh:42: element 15" (the file, the element's line and its tag) for a
/// mesh read from a file, "element 14" (the index) for a generated one.
std::string describe_element(const Mesh& mesh, int e);

/// Nodes per element for a cell and order (Tet: (p+1)(p+2)(p+3)/6; Hex8: 8; Hex20: 20).
int nodes_per_element(CellType cell, int order);

}  // namespace hofem
