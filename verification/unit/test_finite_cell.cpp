// Finite-cell assembly (second seed §4.5 / §5): per-element rules over
// (embedded geometry ∩ cell) in the assembler.
#include "assembly/assembler.hpp"
#include "embedded/embedded_quadrature.hpp"
#include "embedded/finite_cell_quadrature.hpp"
#include "material/material.hpp"
#include "mesh/box_mesh.hpp"

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include <cmath>

namespace hofem {
namespace {

// Geometry that covers every background cell: the per-cell rules of degree m
// integrate the polynomial stiffness integrand exactly (linear elasticity on
// affine boxes: Hex8 gradients have total degree 2, products 4; Hex20 3 and 6),
// so energy, forces and stiffness equal the standard Gauss assembly up to
// rounding (1e-12 relative: sums of ~1e3 terms per entry).
TEST(FiniteCell, FullyCoveredCellsReproduceTheStandardAssembly) {
  struct Case {
    int order, degree;
  };
  for (const Case c : {Case{1, 4}, Case{2, 6}}) {
    const Mesh background = box_mesh(unit_cube(2), CellType::Hexahedron, c.order);
    const Mesh geometry = box_mesh(unit_cube(3), CellType::Tetrahedron, 1);  // not aligned with the cells
    const CellQuadrature fc = finite_cell_quadrature(background, mesh_tetrahedra(geometry), c.degree);
    for (double f : fc.volume_fraction) EXPECT_NEAR(f, 1.0, 1e-13);
    // The cut rules are really used: many more points than the tensor Gauss rule.
    EXPECT_GT(fc.points, 10LL * background.num_elements() * 27);
    const DofMap dofs(background.num_nodes(), background.node_set("xmin"));
    const Assembler standard(background, dofs);
    Assembler cut(background, dofs);
    cut.set_element_quadrature(fc.rules);
    const auto mat = make_material("linear", LameParameters::from_young_poisson(10.0, 0.3));
    Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(background.nodes.data(), 3 * background.num_nodes());
    for (Eigen::Index i = 0; i < x.size(); ++i) x[i] += 0.01 * std::sin(1.7 * i);
    Eigen::VectorXd g1, g2;
    SparseMatrix K1 = standard.new_matrix(), K2 = cut.new_matrix();
    const double E1 = standard.hessian(*mat, x, g1, K1, false), E2 = cut.hessian(*mat, x, g2, K2, false);
    EXPECT_NEAR(E2, E1, 1e-12 * E1) << c.order;
    EXPECT_LE((g2 - g1).norm(), 1e-12 * g1.norm()) << c.order;
    EXPECT_LE((SparseMatrix(K2 - K1)).norm(), 1e-12 * K1.norm()) << c.order;
    EXPECT_NEAR(cut.element_volumes().sum(), 1.0, 1e-13);
  }
}

// Geometry covering part of the grid: cells it misses get empty rules and
// contribute nothing; the cut volume is the geometry's.
TEST(FiniteCell, PartlyCoveredGridIntegratesTheGeometryOnly) {
  const Mesh background = box_mesh(unit_cube(4), CellType::Hexahedron, 1);
  const Mesh geometry = box_mesh(BoxSpec{{0.0, 0.0, 0.0}, {0.6, 1.0, 0.35}, {3, 5, 2}}, CellType::Tetrahedron, 1);
  const CellQuadrature fc = finite_cell_quadrature(background, mesh_tetrahedra(geometry), 2);
  const DofMap dofs(background.num_nodes(), {});
  Assembler cut(background, dofs);
  cut.set_element_quadrature(fc.rules);
  EXPECT_NEAR(cut.element_volumes().sum(), 0.6 * 0.35, 1e-13);
  int empty = 0, partial = 0;
  for (size_t e = 0; e < fc.rules.size(); ++e) {
    empty += fc.rules[e]->rule.size() == 0;
    partial += fc.volume_fraction[e] > 1e-12 && fc.volume_fraction[e] < 1.0 - 1e-12;
  }
  // x <= 0.6 covers 2.4 of 4 cell columns, z <= 0.35 1.4 of 4 layers.
  EXPECT_EQ(empty, 64 - 3 * 4 * 2);
  EXPECT_GT(partial, 0);
  // A wrong-sized rule list is refused.
  EXPECT_THROW(cut.set_element_quadrature(std::vector<std::shared_ptr<const ElementQuadrature>>(3)), std::invalid_argument);
  // Tetrahedral backgrounds are not a box grid.
  EXPECT_THROW(finite_cell_quadrature(box_mesh(unit_cube(1), CellType::Tetrahedron, 1), mesh_tetrahedra(geometry), 2),
               std::invalid_argument);
}

}  // namespace
}  // namespace hofem

namespace hofem {
namespace {

// Second seed §5.3: a sliver cell (fraction below 1e-4) is dropped, and its
// outer nodes leave the system.
TEST(FiniteCell, StabilisationDropsSlivers) {
  const Mesh background = box_mesh(BoxSpec{{0, 0, 0}, {2, 1, 1}, {2, 1, 1}}, CellType::Hexahedron, 1);
  // Geometry: all of cell 0 and a 2e-5 sliver of cell 1 (x in [1, 1.00002]).
  const Mesh geometry = box_mesh(BoxSpec{{0, 0, 0}, {1.00002, 1, 1}, {2, 2, 2}}, CellType::Tetrahedron, 1);
  CellQuadrature fc = finite_cell_quadrature(background, mesh_tetrahedra(geometry), 2);
  const int sliver = fc.volume_fraction[0] < fc.volume_fraction[1] ? 0 : 1;
  EXPECT_NEAR(fc.volume_fraction[sliver], 2e-5, 1e-12);
  const StabilisedCells s = stabilise_finite_cells(background, fc);
  ASSERT_EQ(s.dropped, std::vector<int>{sliver});
  EXPECT_TRUE(s.stabilised.empty());
  EXPECT_EQ(fc.rules[sliver]->rule.size(), 0);
  EXPECT_EQ(active_nodes(background, fc).size(), 8u);  // the sliver's 4 outer nodes carry nothing
}

// The scaled Gauss points make a cut cell's stiffness K_cut + a K_full, so by
// Weyl's inequality its smallest non-rigid eigenvalue (the 7th; 6 rigid modes)
// is at least a = 1e-6 times the full cell's, however small the cut: without
// them a cell cut to 3e-4 near one face is far below that. The volume grows by
// exactly a of the cell.
TEST(FiniteCell, StabilisationBoundsTheCutCellStiffnessFromBelow) {
  const Mesh cell = box_mesh(unit_cube(1), CellType::Hexahedron, 1);
  const Mesh geometry = box_mesh(BoxSpec{{0, 0, 0}, {3e-4, 1, 1}, {1, 2, 2}}, CellType::Tetrahedron, 1);
  const DofMap dofs(cell.num_nodes(), {});
  const auto mat = make_material("linear", LameParameters::from_young_poisson(1.0, 0.3));
  const Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(cell.nodes.data(), 3 * cell.num_nodes());
  auto seventh_eigenvalue = [&](const CellQuadrature* fc, double* volume) {
    Assembler a(cell, dofs);
    if (fc) a.set_element_quadrature(fc->rules);
    SparseMatrix K = a.new_matrix();
    Eigen::VectorXd g;
    a.hessian(*mat, x, g, K, false);
    if (volume) *volume = a.element_volumes()[0];
    return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Eigen::MatrixXd(K)).eigenvalues()[6];
  };
  const double full = seventh_eigenvalue(nullptr, nullptr);
  CellQuadrature fc = finite_cell_quadrature(cell, mesh_tetrahedra(geometry), 2);
  double volume = 0.0;
  const double bare = seventh_eigenvalue(&fc, &volume);
  EXPECT_NEAR(volume, 3e-4, 1e-15);
  EXPECT_LT(bare, 1e-6 * full) << "the test needs a cut that is weaker than the stabilisation";
  const StabilisedCells s = stabilise_finite_cells(cell, fc);
  ASSERT_EQ(s.stabilised, std::vector<int>{0});
  const double stabilised = seventh_eigenvalue(&fc, &volume);
  EXPECT_NEAR(volume, 3e-4 + 1e-6, 1e-15);
  EXPECT_GE(stabilised, 1e-6 * full * (1.0 - 1e-9));
}

}  // namespace
}  // namespace hofem
