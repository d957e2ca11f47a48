#pragma once
// Gmsh's reference node coordinates, in Gmsh's node order, as published by Gmsh:
// the "Node ordering" section of the Gmsh reference manual and Gmsh 4.7's
// gmsh.model.mesh.getElementProperties output (as recorded in
// inducer/gmsh_interop, gmsh_interop/node_tuples.py), which agrees with Gmsh's
// Numeric/pointsGenerators.cpp. Facts carried over as data, not code.
#include "quadrature/cell_type.hpp"

#include <array>
#include <string>
#include <vector>

namespace hofem::verification {

struct GmshNodeTable {
  std::string name;  // Gmsh element name
  CellType cell;
  int order;
  std::vector<std::array<double, 3>> nodes;
};

inline const std::vector<GmshNodeTable>& gmsh_node_tables() {
  constexpr double t = 1.0 / 3, tt = 2.0 / 3, q = 0.25, h = 0.5, tq = 0.75;
  static const std::vector<GmshNodeTable> tables = {
      {"Line3", CellType::Segment, 2, {{-1, 0, 0}, {1, 0, 0}, {0, 0, 0}}},
      {"Line4", CellType::Segment, 3, {{-1, 0, 0}, {1, 0, 0}, {-t, 0, 0}, {t, 0, 0}}},
      {"Tri3", CellType::Triangle, 1, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}},
      {"Tri6", CellType::Triangle, 2, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {h, 0, 0}, {h, h, 0}, {0, h, 0}}},
      {"Tri10", CellType::Triangle, 3,
       {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {t, 0, 0}, {tt, 0, 0}, {tt, t, 0}, {t, tt, 0}, {0, tt, 0}, {0, t, 0}, {t, t, 0}}},
      {"Tri15", CellType::Triangle, 4,
       {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {q, 0, 0}, {h, 0, 0}, {tq, 0, 0}, {tq, q, 0}, {h, h, 0}, {q, tq, 0},
        {0, tq, 0}, {0, h, 0}, {0, q, 0}, {q, q, 0}, {h, q, 0}, {q, h, 0}}},
      {"Tet4", CellType::Tetrahedron, 1, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}},
      {"Tet10", CellType::Tetrahedron, 2,
       {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {h, 0, 0}, {h, h, 0}, {0, h, 0}, {0, 0, h}, {0, h, h}, {h, 0, h}}},
      {"Tet20", CellType::Tetrahedron, 3,
       {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {t, 0, 0}, {tt, 0, 0}, {tt, t, 0}, {t, tt, 0}, {0, tt, 0},
        {0, t, 0}, {0, 0, tt}, {0, 0, t}, {0, t, tt}, {0, tt, t}, {t, 0, tt}, {tt, 0, t}, {t, t, 0}, {t, 0, t},
        {0, t, t}, {t, t, t}}},
      {"Tet35", CellType::Tetrahedron, 4,
       {{0, 0, 0},   {1, 0, 0},   {0, 1, 0},   {0, 0, 1},   {q, 0, 0},   {h, 0, 0},  {tq, 0, 0},
        {tq, q, 0},  {h, h, 0},   {q, tq, 0},  {0, tq, 0},  {0, h, 0},   {0, q, 0},  {0, 0, tq},
        {0, 0, h},   {0, 0, q},   {0, q, tq},  {0, h, h},   {0, tq, q},  {q, 0, tq}, {h, 0, h},
        {tq, 0, q},  {q, q, 0},   {q, h, 0},   {h, q, 0},   {q, 0, q},   {h, 0, q},  {q, 0, h},
        {0, q, q},   {0, q, h},   {0, h, q},   {q, q, h},   {h, q, q},   {q, h, q},  {q, q, q}}},
      {"Hex8", CellType::Hexahedron, 1,
       {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}}},
      {"Hex20", CellType::Hexahedron, 2,
       {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1},
        {-1, 1, 1},   {0, -1, -1}, {-1, 0, -1}, {-1, -1, 0}, {1, 0, -1}, {1, -1, 0}, {0, 1, -1},
        {1, 1, 0},    {-1, 1, 0},  {0, -1, 1},  {-1, 0, 1},  {1, 0, 1},  {0, 1, 1}}},
  };
  return tables;
}

}  // namespace hofem::verification
