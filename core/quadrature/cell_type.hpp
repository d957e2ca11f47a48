#pragma once
// Reference cells of hofem.
//
//  segment      [-1, 1]                         (Gauss–Legendre, Gmsh line)
//  triangle     unit simplex: vertices 0, e1, e2 (area 1/2)
//  tetrahedron  unit simplex: vertices 0, e1, e2, e3 (volume 1/6)
//  quadrilateral [-1, 1]^2,  hexahedron [-1, 1]^3  (tensor Gauss, Gmsh Hex8/Hex20)
//
// The simplices use the unit simplex because that is Gmsh's reference element
// and the thesis' isoparametric space (thesis eq. 4.27, 4.33).
#include <Eigen/Core>

#include <array>
#include <optional>
#include <string>
#include <string_view>

namespace hofem {

enum class CellType { Segment, Triangle, Tetrahedron, Quadrilateral, Hexahedron };

/// Spatial dimension of the reference cell.
int dimension(CellType cell);
/// Canonical lower-case name ("segment", "triangle", "tet", "quad", "hex").
std::string_view name(CellType cell);
/// Parses a cell name; accepts the canonical names and the long forms
/// ("tetrahedron", "quadrilateral", "hexahedron", "line"). Empty on failure.
std::optional<CellType> parse_cell(std::string_view text);
/// The list of names parse_cell accepts, for error messages.
std::string cell_choices();
/// Measure (length, area, volume) of the reference cell.
double reference_volume(CellType cell);
/// Signed distance-like margin of a point from the reference cell's boundary,
/// in reference coordinates: for simplices the smallest barycentric coordinate,
/// for tensor cells 1 - max|x_i|. Positive strictly inside, zero on the boundary.
double interior_margin(CellType cell, const Eigen::Ref<const Eigen::VectorXd>& x);
/// Vertices of the reference cell, one per column (Gmsh vertex order).
Eigen::MatrixXd reference_vertices(CellType cell);

/// Corner faces of the tetrahedron (face i opposite vertex i) and of the
/// hexahedron, as Gmsh vertex indices, each ordered so that the right-hand
/// rule gives the outward normal of a positively oriented cell. The one home of
/// these tables: boundary extraction, surface sampling and partition quality
/// all key faces by them (ctest CellType.CornerFacesAreOutwardBoundaryFaces).
inline constexpr std::array<std::array<int, 3>, 4> kTetrahedronFaces{{{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}}};
inline constexpr std::array<std::array<int, 4>, 6> kHexahedronFaces{
    {{0, 3, 2, 1}, {0, 1, 5, 4}, {0, 4, 7, 3}, {1, 2, 6, 5}, {2, 3, 7, 6}, {4, 5, 6, 7}}};

}  // namespace hofem
