#include "quadrature/cell_type.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace hofem {

int dimension(CellType cell) {
  switch (cell) {
    case CellType::Segment: return 1;
    case CellType::Triangle:
    case CellType::Quadrilateral: return 2;
    case CellType::Tetrahedron:
    case CellType::Hexahedron: return 3;
  }
  throw std::logic_error("dimension: unknown cell");
}

std::string_view name(CellType cell) {
  switch (cell) {
    case CellType::Segment: return "segment";
    case CellType::Triangle: return "triangle";
    case CellType::Tetrahedron: return "tet";
    case CellType::Quadrilateral: return "quad";
    case CellType::Hexahedron: return "hex";
  }
  throw std::logic_error("name: unknown cell");
}

std::optional<CellType> parse_cell(std::string_view t) {
  if (t == "segment" || t == "line") return CellType::Segment;
  if (t == "triangle" || t == "tri") return CellType::Triangle;
  if (t == "tet" || t == "tetrahedron") return CellType::Tetrahedron;
  if (t == "quad" || t == "quadrilateral") return CellType::Quadrilateral;
  if (t == "hex" || t == "hexahedron") return CellType::Hexahedron;
  return std::nullopt;
}

std::string cell_choices() { return "segment, triangle, tet, quad, hex"; }

double reference_volume(CellType cell) {
  switch (cell) {
    case CellType::Segment: return 2.0;
    case CellType::Triangle: return 0.5;
    case CellType::Tetrahedron: return 1.0 / 6.0;
    case CellType::Quadrilateral: return 4.0;
    case CellType::Hexahedron: return 8.0;
  }
  throw std::logic_error("reference_volume: unknown cell");
}

double interior_margin(CellType cell, const Eigen::Ref<const Eigen::VectorXd>& x) {
  switch (cell) {
    case CellType::Triangle:
    case CellType::Tetrahedron: {
      // Barycentric coordinates of the unit simplex: lambda_0 = 1 - sum(x), lambda_i = x_i.
      return std::min(1.0 - x.sum(), x.minCoeff());
    }
    case CellType::Segment:
    case CellType::Quadrilateral:
    case CellType::Hexahedron: return 1.0 - x.cwiseAbs().maxCoeff();
  }
  throw std::logic_error("interior_margin: unknown cell");
}

Eigen::MatrixXd reference_vertices(CellType cell) {
  switch (cell) {
    case CellType::Segment: return (Eigen::MatrixXd(1, 2) << -1, 1).finished();
    case CellType::Triangle:
      return (Eigen::MatrixXd(2, 3) << 0, 1, 0,  //
              0, 0, 1)
          .finished();
    case CellType::Tetrahedron:
      return (Eigen::MatrixXd(3, 4) << 0, 1, 0, 0,  //
              0, 0, 1, 0,                           //
              0, 0, 0, 1)
          .finished();
    case CellType::Quadrilateral:
      return (Eigen::MatrixXd(2, 4) << -1, 1, 1, -1,  //
              -1, -1, 1, 1)
          .finished();
    case CellType::Hexahedron:
      return (Eigen::MatrixXd(3, 8) << -1, 1, 1, -1, -1, 1, 1, -1,  //
              -1, -1, 1, 1, -1, -1, 1, 1,                           //
              -1, -1, -1, -1, 1, 1, 1, 1)
          .finished();
  }
  throw std::logic_error("reference_vertices: unknown cell");
}

}  // namespace hofem
