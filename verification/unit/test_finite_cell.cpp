// Finite-cell assembly (Longva et al. 2020 §4.5 / §5): per-element rules over
// (embedded geometry ∩ cell) in the assembler.
#include "assembly/assembler.hpp"
#include "embedded/embedded_quadrature.hpp"
#include "embedded/finite_cell_quadrature.hpp"
#include "material/material.hpp"
#include "embedded/embedded_points.hpp"
#include "mesh/box_mesh.hpp"
#include "mesh/tube_mesh.hpp"
#include "problem/static_elasticity.hpp"

#include <Eigen/Eigenvalues>
#include <fmt/format.h>
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
  // A curved (non-affine) background cell is refused, naming the element.
  Mesh curved = box_mesh(unit_cube(1), CellType::Tetrahedron, 2);
  curved.nodes(0, curved.elements(4, 3)) += 0.05;  // bend an edge of element 3
  try {
    finite_cell_quadrature(curved, mesh_tetrahedra(geometry), 2);
    ADD_FAILURE() << "a curved cell was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("is not affine"), std::string::npos) << e.what();  // element 2 or 3 (shared edge)
  }
}

}  // namespace
}  // namespace hofem

namespace hofem {
namespace {

// Longva et al. 2020 §5.3: a sliver cell (fraction below 1e-4) is dropped, and its
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
  // The sliver's 4 outer nodes carry nothing: the problems constrain them.
  EXPECT_EQ(unsupported_nodes(background, fc.element_rules()).size(), 4u);
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

// Folding the stabilisation into the simplified rule (simplify_degree) leaves at
// most C(m+3, 3) points and the same stiffness: the linear-elastic Hex8 stiffness
// of an affine cell is a polynomial of degree 2 (d - 1) = 4 <= m, so the folded
// rule reproduces the unfolded K to the LP's moment tolerance (1e-11 relative to
// the weights' sum; K's entries are O(1), so 1e-9 of max |K| is far above that
// round-off and far below the stabilised part, 1e-6 of the full cell).
TEST(FiniteCell, FoldedStabilisationKeepsTheStiffnessWithFewerPoints) {
  const Mesh cell = box_mesh(unit_cube(1), CellType::Hexahedron, 1);
  const Mesh geometry = box_mesh(BoxSpec{{0, 0, 0}, {0.3, 1, 1}, {1, 2, 2}}, CellType::Tetrahedron, 1);
  const DofMap dofs(cell.num_nodes(), {});
  const auto mat = make_material("linear", LameParameters::from_young_poisson(1.0, 0.3));
  const Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(cell.nodes.data(), 3 * cell.num_nodes());
  auto stiffness = [&](const CellQuadrature& fc) {
    Assembler a(cell, dofs);
    a.set_element_quadrature(fc.rules);
    SparseMatrix K = a.new_matrix();
    Eigen::VectorXd g;
    a.hessian(*mat, x, g, K, false);
    return Eigen::MatrixXd(K);
  };
  CellQuadrature unfolded = finite_cell_quadrature(cell, mesh_tetrahedra(geometry));
  CellQuadrature folded = unfolded;
  const int degree = unfolded.stiffness_degree;
  ASSERT_EQ(degree, 4);
  stabilise_finite_cells(cell, unfolded);
  FiniteCellStabilisation options;
  options.simplify_degree = degree;
  const StabilisedCells s = stabilise_finite_cells(cell, folded, options);
  ASSERT_EQ(s.folded, 1);
  const int bound = (degree + 1) * (degree + 2) * (degree + 3) / 6;  // C(m+3, 3) = 35
  EXPECT_LE(folded.rules[0]->rule.size(), bound);
  EXPECT_GT(unfolded.rules[0]->rule.size(), bound);
  const Eigen::MatrixXd K0 = stiffness(unfolded), K1 = stiffness(folded);
  EXPECT_LE((K1 - K0).cwiseAbs().maxCoeff(), 1e-9 * K0.cwiseAbs().maxCoeff());
  // The folded weights still hold the stabilised volume: 0.3 of the cell plus 1e-6 of it.
  EXPECT_NEAR(folded.rules[0]->rule.weights.sum(), 8.0 * (0.3 + 1e-6), 1e-12);
}

// Static problems stabilise the stiffness only: their mass rules carry the loads,
// which must integrate over the body alone (the cut rule's own object is kept).
TEST(FiniteCell, StabilisationCanLeaveTheMassRulesAlone) {
  const Mesh cell = box_mesh(unit_cube(1), CellType::Hexahedron, 1);
  const Mesh geometry = box_mesh(BoxSpec{{0, 0, 0}, {0.3, 1, 1}, {1, 2, 2}}, CellType::Tetrahedron, 1);
  for (const bool mass : {true, false}) {
    CellQuadrature fc = finite_cell_quadrature(cell, mesh_tetrahedra(geometry), 2);
    const auto cut_mass = fc.mass_rules[0];
    const int cut_stiffness_points = fc.rules[0]->rule.size();
    FiniteCellStabilisation options;
    options.mass = mass;
    stabilise_finite_cells(cell, fc, options);
    EXPECT_GT(fc.rules[0]->rule.size(), cut_stiffness_points);  // the Gauss points were added
    EXPECT_EQ(fc.mass_rules[0] == cut_mass, !mass);
    EXPECT_NEAR(fc.mass_rules[0]->rule.weights.sum(), 8.0 * (0.3 + (mass ? 1e-6 : 0.0)), 1e-14);
  }
}

}  // namespace
}  // namespace hofem

namespace hofem {
namespace {

Eigen::VectorXd rest_positions(const Mesh& m) { return Eigen::Map<const Eigen::VectorXd>(m.nodes.data(), 3 * m.num_nodes()); }

// Linear-elastic forces and stiffness of two assemblers of one mesh agree to rtol at x.
void expect_same_elastic_system(const Assembler& a, const Assembler& b, const Eigen::VectorXd& x, double rtol,
                                const std::string& what) {
  const auto mat = make_material("linear", LameParameters::from_young_poisson(10.0, 0.3));
  Eigen::VectorXd ga, gb;
  SparseMatrix Ka = a.new_matrix(), Kb = b.new_matrix();
  a.hessian(*mat, x, ga, Ka, false);
  b.hessian(*mat, x, gb, Kb, false);
  EXPECT_LE((gb - ga).norm(), rtol * ga.norm()) << what;
  EXPECT_LE((SparseMatrix(Kb - Ka)).norm(), rtol * Ka.norm()) << what;
}

// Tetrahedral backgrounds (Tet4, straight Tet10): a fully covered grid gives the
// standard assembly (degree 2p rules integrate the linear-elastic integrand,
// of degree 2(p-1), exactly: 1e-12 relative, rounding of ~1e3-term sums).
TEST(FiniteCell, TetBackgroundsReproduceTheStandardAssembly) {
  for (int order : {1, 2}) {
    const Mesh background = box_mesh(unit_cube(2), CellType::Tetrahedron, order);
    const Mesh geometry_tets = box_mesh(unit_cube(3), CellType::Tetrahedron, 1);
    FiniteCellOptions o;
    o.standard_rule_inside = false;  // keep the clipped rules in every (uncut) cell
    const CellQuadrature fc = finite_cell_quadrature(background, mesh_tetrahedra(geometry_tets), o);
    for (double f : fc.volume_fraction) EXPECT_NEAR(f, 1.0, 1e-12);
    const DofMap dofs(background.num_nodes(), background.node_set("xmin"));
    const Assembler standard(background, dofs);
    Assembler cut(background, dofs);
    cut.set_element_rules(fc.element_rules());
    Eigen::VectorXd x = rest_positions(background);
    for (Eigen::Index i = 0; i < x.size(); ++i) x[i] += 0.01 * std::sin(1.7 * i);
    expect_same_elastic_system(standard, cut, x, 1e-12, fmt::format("order {}", order));
    // Mass rules of degree 2p: the consistent mass too.
    const SparseMatrix M1 = standard.mass_matrix(2.0, 2 * order), M2 = cut.mass_matrix(2.0, 2 * order);
    EXPECT_LE((SparseMatrix(M2 - M1)).norm(), 1e-12 * M1.norm()) << order;
  }
}

// The LP simplification (§4.4) keeps the stiffness of cut Tet10 cells: their
// degree-4 rules stay exact for the degree-2 linear-elastic integrand, so the
// simplified and the raw clipped rules agree to rounding (1e-11 relative: the
// simplified weights carry the LP refinement's ~1e-14 moment residual times the
// conditioning of the Chebyshev basis); each cut cell keeps <= C(4+3,3) = 35 points.
TEST(FiniteCell, SimplifiedCutCellRulesKeepTheStiffnessAndMass) {
  const Mesh background = box_mesh(unit_cube(2), CellType::Tetrahedron, 2);
  const Mesh geometry = box_mesh(BoxSpec{{0.0, 0.0, 0.0}, {0.7, 0.9, 0.62}, {4, 5, 3}}, CellType::Tetrahedron, 1);
  FiniteCellOptions raw;
  raw.simplify = false;
  const CellQuadrature a = finite_cell_quadrature(background, mesh_tetrahedra(geometry), raw);
  const CellQuadrature b = finite_cell_quadrature(background, mesh_tetrahedra(geometry));  // simplified
  EXPECT_EQ(a.stiffness_degree, 4);
  int cut = 0;
  for (int e = 0; e < background.num_elements(); ++e)
    if (b.points_before[e] > 0) {
      ++cut;
      EXPECT_LE(b.points_after[e], 35) << e;
      EXPECT_LT(b.moment_residual[e], 1e-12) << e;  // per cell, as reported; LP refinement reaches rounding
      if (b.points_before[e] > 35) {
        EXPECT_LT(b.points_after[e], b.points_before[e]) << e;
      }
    }
  EXPECT_GT(cut, 10);
  EXPECT_EQ(b.simplification_failures, 0);
  EXPECT_LT(b.max_moment_residual, 1e-12);
  const std::vector<int> fixed = unsupported_nodes(background, a.element_rules());
  EXPECT_EQ(fixed, unsupported_nodes(background, b.element_rules()));
  const DofMap dofs(background.num_nodes(), fixed);
  Assembler A(background, dofs), B(background, dofs);
  A.set_element_rules(a.element_rules());
  B.set_element_rules(b.element_rules());
  Eigen::VectorXd x = rest_positions(background);
  for (Eigen::Index i = 0; i < x.size(); ++i) x[i] += 0.01 * std::cos(0.9 * i);
  expect_same_elastic_system(A, B, x, 1e-11, "simplified vs clipped rules");
  EXPECT_NEAR(B.element_volumes().sum(), 0.7 * 0.9 * 0.62, 1e-13);
}

// Mass rules integrate the embedded geometry's inertia: with sum_i N_i = 1 and
// sum_j N_j X_j = X on affine cells, 1^T M 1 is the mass and 1^T M X its first
// moment, whatever the background, so the centre of mass is the geometry's
// (exact to rounding: 1e-13), as Longva et al. 2020 Fig. 6 needs.
TEST(FiniteCell, MassRulesGiveTheGeometrysMassAndCentreOfMass) {
  const Mesh geometry = box_mesh(BoxSpec{{0.1, 0.2, 0.05}, {0.8, 0.5, 0.3}, {3, 2, 2}}, CellType::Tetrahedron, 1);
  const Eigen::Vector3d centre(0.45, 0.35, 0.175);
  const double volume = 0.7 * 0.3 * 0.25, rho = 3.0;
  for (auto [cell, order] : {std::pair{CellType::Hexahedron, 1}, std::pair{CellType::Hexahedron, 2},
                             std::pair{CellType::Tetrahedron, 1}, std::pair{CellType::Tetrahedron, 2}}) {
    const Mesh background = box_mesh(unit_cube(1), cell, order);  // one coarse cell (hex) / 6 tets
    const CellQuadrature fc = finite_cell_quadrature(background, mesh_tetrahedra(geometry));
    const DofMap dofs(background.num_nodes(), unsupported_nodes(background, fc.element_rules()));
    const DofMap all(background.num_nodes(), {});
    Assembler a(background, all);
    a.set_element_rules(fc.element_rules());
    const Eigen::VectorXd X = rest_positions(background);
    Eigen::VectorXd ones(X.size());
    for (int n = 0; n < background.num_nodes(); ++n) ones.segment<3>(3 * n) = Eigen::Vector3d::Ones();
    const Eigen::VectorXd MX = a.mass_action(rho, 2 * order, X), M1 = a.mass_action(rho, 2 * order, ones);
    double mass = 0.0;
    Eigen::Vector3d moment = Eigen::Vector3d::Zero();
    for (int n = 0; n < background.num_nodes(); ++n) {
      mass += M1[3 * n];
      moment += MX.segment<3>(3 * n);
    }
    EXPECT_NEAR(mass, rho * volume, 1e-13) << name(cell) << order;
    EXPECT_LE((moment / mass - centre).norm(), 1e-13) << name(cell) << order;
    EXPECT_NEAR(a.lumped_mass(rho, 2 * order, MassLumping::HRZ).sum() / 3.0, rho * volume, 1e-13);
  }
}

// A geometry made of whole background cells: the finite-cell problem is the
// conforming one on those cells (empty cells' nodes are fixed as unsupported),
// so a static solve under gravity gives the same displacements to solver rounding.
TEST(FiniteCell, StaticProblemOnWholeCellsMatchesTheConformingMesh) {
  const Mesh background = box_mesh(unit_cube(2), CellType::Hexahedron, 2);
  const Mesh conforming = box_mesh(BoxSpec{{0, 0, 0}, {1, 1, 0.5}, {2, 2, 1}}, CellType::Hexahedron, 2);
  const Mesh geometry = box_mesh(BoxSpec{{0, 0, 0}, {1, 1, 0.5}, {3, 3, 2}}, CellType::Tetrahedron, 1);
  const auto mat = make_material("neohookean", LameParameters::from_young_poisson(1e4, 0.3));
  const VectorField gravity = [](const Eigen::Vector3d&) { return Eigen::Vector3d(0, 0, -300.0); };
  StaticOptions o;
  const CellQuadrature fc = finite_cell_quadrature(background, mesh_tetrahedra(geometry));
  o.element_rules = fc.element_rules();
  StaticElasticity fcm(background, *mat, {{background.node_set("xmin"), {}}}, gravity, o);
  StaticElasticity fem(conforming, *mat, {{conforming.node_set("xmin"), {}}}, gravity);
  ASSERT_TRUE(fcm.solve().converged);
  ASSERT_TRUE(fem.solve().converged);
  EXPECT_EQ(fcm.dofs().num_free(), fem.dofs().num_free());
  double worst = 0.0;
  for (int n = 0; n < conforming.num_nodes(); ++n)
    for (int m = 0; m < background.num_nodes(); ++m)
      if ((background.nodes.col(m) - conforming.nodes.col(n)).norm() < 1e-12)
        worst = std::max(worst, (fcm.displacement().segment<3>(3 * m) - fem.displacement().segment<3>(3 * n)).norm());
  EXPECT_LE(worst, 1e-9 * fem.displacement().cwiseAbs().maxCoeff());  // Newton stops at ~1e-10 relative
  EXPECT_GT(fem.displacement().cwiseAbs().maxCoeff(), 1e-3);
}

// Embedded points follow the background field; a linear field is in every
// basis' space, so it is reproduced exactly also where a point is extrapolated
// from a neighbour (its own cell inactive): 1e-13, rounding.
TEST(FiniteCell, EmbeddedPointsInterpolateAndExtrapolate) {
  for (auto [cell, order] : {std::pair{CellType::Hexahedron, 2}, std::pair{CellType::Tetrahedron, 2}}) {
    const Mesh background = box_mesh(unit_cube(2), cell, order);
    Eigen::Matrix3Xd points(3, 4);
    points << 0.1, 0.6, 0.951, 0.3, 0.2, 0.7, 0.873, 0.3, 0.3, 0.4, 0.962, 0.0;  // point 2 off every tet face
    std::vector<char> active(background.num_elements(), 1);
    EmbeddedPointMap first = locate_embedded_points(background, points, active);
    EXPECT_EQ(first.num_extrapolated, 0);
    active[first.element[2]] = 0;  // "drop" the cell of point 2
    const EmbeddedPointMap map = locate_embedded_points(background, points, active);
    EXPECT_EQ(map.num_extrapolated, 1) << name(cell);
    EXPECT_TRUE(map.extrapolated[2]);
    EXPECT_NE(map.element[2], first.element[2]);
    Eigen::Matrix3d G;
    G << 0.1, -0.2, 0.3, 0.05, 0.0, 0.4, -0.1, 0.2, 0.0;
    Eigen::VectorXd u(3 * background.num_nodes());
    for (int n = 0; n < background.num_nodes(); ++n) u.segment<3>(3 * n) = G * background.nodes.col(n);
    const Eigen::Matrix3Xd at = interpolate_at_points(background, map, u);
    EXPECT_LE((at - G * points).cwiseAbs().maxCoeff(), 1e-13);
  }
  const Mesh background = box_mesh(unit_cube(1), CellType::Hexahedron, 1);
  Eigen::Matrix3Xd bad(3, 1);
  bad << 0.5, std::nan(""), 0.5;
  EXPECT_THROW(locate_embedded_points(background, bad), std::invalid_argument);
  EXPECT_THROW(locate_embedded_points(background, Eigen::Matrix3Xd::Zero(3, 1), std::vector<char>(1, 0)),
               std::invalid_argument);
}

// The boundary of a tet mesh of the unit cube: 2 x 2 x 2 cubes of 6 tets give 2
// triangles per face square, total area 6, outward (divergence theorem:
// integral of X . n over the surface = 3 V = 3).
TEST(FiniteCell, BoundarySurfaceIsClosedAndOutward) {
  const Mesh tets = box_mesh(unit_cube(2), CellType::Tetrahedron, 1);
  std::vector<int> vertex_of;
  const Mesh s = boundary_surface(tets, &vertex_of);
  EXPECT_EQ(s.num_elements(), 6 * 4 * 2);
  EXPECT_EQ(s.num_nodes(), 26);  // 27 grid vertices but the centre
  double area = 0.0, flux = 0.0;
  for (int t = 0; t < s.num_elements(); ++t) {
    const Eigen::Vector3d a = s.nodes.col(s.elements(0, t)), b = s.nodes.col(s.elements(1, t)), c = s.nodes.col(s.elements(2, t));
    const Eigen::Vector3d n2 = (b - a).cross(c - a);  // twice the area times the normal
    area += 0.5 * n2.norm();
    flux += 0.5 * n2.dot((a + b + c) / 3.0);
    EXPECT_EQ(tets.nodes.col(vertex_of[s.elements(0, t)]), a);
  }
  EXPECT_NEAR(area, 6.0, 1e-13);
  EXPECT_NEAR(flux, 3.0, 1e-13);
}

}  // namespace
}  // namespace hofem

#include "solver/additive_schwarz.hpp"

namespace hofem {
namespace {

// Longva et al. 2020 §5.2: blocks only for cut cells under a volume fraction of 0.5,
// Jacobi elsewhere, passed through the mesh view, and CG / MINRES with it
// solve the stabilised finite-cell problem to the direct solver's answer
// (1e-6 relative: the Krylov stopping rule is 1e-10 on the residual, times the
// condition number of the stabilised system).
TEST(FiniteCell, AdditiveSchwarzBlocksCutCellsAndSolvesTheSystem) {
  const Mesh background = box_mesh(BoxSpec{{0, 0, 0}, {4.0 / 3, 4.0 / 3, 4.0 / 3}, {4, 4, 4}}, CellType::Hexahedron, 2);
  const Mesh geometry = box_mesh(BoxSpec{{0, 0, 0}, {1.02, 1.1, 0.9}, {3, 3, 3}}, CellType::Tetrahedron, 1);
  CellQuadrature fc = finite_cell_quadrature(background, mesh_tetrahedra(geometry));
  stabilise_finite_cells(background, fc);
  const std::vector<int> blocks = schwarz_block_elements(fc);
  ASSERT_FALSE(blocks.empty());
  for (int e : blocks) EXPECT_LT(fc.volume_fraction[e], 0.5);
  // x = 1.02 cuts the fourth column of cells to a fraction 0.06, z = 0.9 the third layer to 0.7.
  int thin = 0;
  for (int e = 0; e < background.num_elements(); ++e) thin += fc.volume_fraction[e] > 0 && fc.volume_fraction[e] < 0.5;
  EXPECT_EQ(static_cast<int>(blocks.size()), thin);

  const DofMap dofs(background.num_nodes(), unsupported_nodes(background, fc.element_rules()));
  AdditiveSchwarzPreconditioner some, none;
  const std::vector<int> empty;
  some.set_mesh_view({&background, &dofs, &blocks});
  none.set_mesh_view({&background, &dofs, &empty});
  Assembler a(background, dofs);
  a.set_element_rules(fc.element_rules());
  SparseMatrix K = a.new_matrix();
  Eigen::VectorXd g;
  const auto mat = make_material("linear", LameParameters::from_young_poisson(1e3, 0.3));
  a.hessian(*mat, rest_positions(background), g, K, false);
  const SparseMatrix A = a.mass_matrix(1.0, 4) + SparseMatrix((1.0 / 3600.0) * K);
  ASSERT_TRUE(some.setup(A)) << some.last_error();
  ASSERT_TRUE(none.setup(A)) << none.last_error();
  EXPECT_EQ(some.num_blocks(), static_cast<int>(blocks.size()));
  EXPECT_EQ(none.num_blocks(), 0);
  EXPECT_EQ(none.num_uncovered(), dofs.num_free());

  // Static problem under gravity, clamped at x = 0: direct vs CG / MINRES + Schwarz.
  const VectorField gravity = [](const Eigen::Vector3d&) { return Eigen::Vector3d(0, 0, -10.0); };
  Eigen::VectorXd reference;
  for (const char* solver : {"cholmod", "cg+schwarz", "minres+schwarz"}) {
    StaticOptions o;
    o.element_rules = fc.element_rules();
    o.preconditioner_blocks = blocks;
    o.solver = SolverSpec::parse(solver);
    StaticElasticity problem(background, *mat, {{background.node_set("xmin"), {}}}, gravity, o);
    ASSERT_TRUE(problem.solve().converged) << solver;
    if (reference.size() == 0) {
      reference = problem.displacement();
      continue;
    }
    EXPECT_LE((problem.displacement() - reference).norm(), 1e-6 * reference.norm()) << solver;
  }
}

}  // namespace
}  // namespace hofem

namespace hofem {
namespace {

// Moment-fitted mass rules (fit_mass, the scenes' choice) give the clipped
// rules' consistent mass matrix and gravity load: N_i N_j (and N_i) are
// polynomials of degree <= 2 x the highest total degree (Hex8: 6, Hex20: 8) on an
// affine cell, which the fitted rule integrates as the clipped one does, to
// rounding. Bound: the moments agree to ~1e-15 of the weights' |sum| and the
// fitted weights' sum |w| / sum w stays below ~3 (measured 2.4), so the entries
// agree to ~1e-14 of the largest; 1e-13 leaves a margin of 10. The stiffness
// rules are not touched (the same points and weights, bit for bit).
TEST(FiniteCell, FittedMassRulesGiveTheClippedMassMatrix) {
  const std::vector<Tetrahedron> tube =
      mesh_tetrahedra(hollow_cylinder_mesh(0.5, 1.0, 3.0, 1, 16, 8, CellType::Tetrahedron, 1));
  for (int order : {1, 2}) {
    const Mesh background = box_mesh(BoxSpec{{-1, -1, 0}, {1, 1, 3}, {2, 2, 3}}, CellType::Hexahedron, order);
    FiniteCellOptions clipped, fitted;
    fitted.fit_mass = true;
    const CellQuadrature a = finite_cell_quadrature(background, tube, clipped);
    const CellQuadrature b = finite_cell_quadrature(background, tube, fitted);
    const int M = (b.mass_degree + 1) * (b.mass_degree + 2) * (b.mass_degree + 3) / 6;
    int cut = 0;
    for (int e = 0; e < background.num_elements(); ++e) {
      if (!b.mass_rules[e] || a.points_before[e] == 0) continue;
      ++cut;
      EXPECT_EQ(b.mass_rules[e]->rule.size(), M) << e;
      EXPECT_GT(a.mass_rules[e]->rule.size(), 10 * M) << e;
      EXPECT_EQ(a.rules[e]->rule.points, b.rules[e]->rule.points) << e;
      EXPECT_EQ(a.rules[e]->rule.weights, b.rules[e]->rule.weights) << e;
    }
    EXPECT_EQ(cut, 12);
    EXPECT_EQ(b.mass_fit_failures, 0);
    EXPECT_LE(b.max_mass_moment_residual, 1e-14);
    const DofMap dofs(background.num_nodes(), {});
    Assembler A(background, dofs), B(background, dofs);
    A.set_element_rules(a.element_rules());
    B.set_element_rules(b.element_rules());
    const SparseMatrix M0 = A.mass_matrix(1000.0, 2 * order), M1 = B.mass_matrix(1000.0, 2 * order);
    const double scale = M0.coeffs().cwiseAbs().maxCoeff();
    EXPECT_LE(SparseMatrix(M1 - M0).coeffs().cwiseAbs().maxCoeff(), 1e-13 * scale) << order;
    const auto gravity = [](const Eigen::Vector3d&) { return Eigen::Vector3d(0.0, 0.0, -9.81); };
    const Eigen::VectorXd f0 = A.body_force_vector(gravity, 2 * order), f1 = B.body_force_vector(gravity, 2 * order);
    EXPECT_LE((f1 - f0).cwiseAbs().maxCoeff(), 1e-13 * f0.cwiseAbs().maxCoeff()) << order;
  }
}

}  // namespace
}  // namespace hofem
