// The default quadrature degrees (basis/quadrature_degrees.hpp), pinned: each
// expected value below is derived by hand from the integrand's polynomial
// degree, not computed by the function under test, and the sites that used to
// compute their own degrees are held to the function.
#include "assembly/assembler.hpp"
#include "assembly/dof_map.hpp"
#include "basis/element_orders.hpp"
#include "basis/quadrature_degrees.hpp"
#include "mesh/box_mesh.hpp"
#include "study/manufactured_solution.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace hofem {
namespace {

using D = IntegrationDomain;

struct Pinned {
  CellType cell;
  int order;
  D domain;
  int stiffness, mass, load;
};

// Tet p: basis degree p, gradients p - 1. Affine + constant tangent: the
// product of two gradients, 2(p - 1), at least 1. Otherwise 2p. Mass N_i N_j:
// 2p. Load N_i f: 2p + 2.
// Hex (uncut): 2p per direction. Cut hex: total degree, Hex8 highest monomial
// xyz (3), Hex20 x^2yz (4): stiffness 2(d - 1) = 4 / 6, mass 2d = 6 / 8.
constexpr Pinned kPinned[] = {
    {CellType::Tetrahedron, 1, D::Cell, 2, 2, 4},    {CellType::Tetrahedron, 1, D::Affine, 1, 2, 4},
    {CellType::Tetrahedron, 2, D::Cell, 4, 4, 6},    {CellType::Tetrahedron, 2, D::Affine, 2, 4, 6},
    {CellType::Tetrahedron, 3, D::Cell, 6, 6, 8},    {CellType::Tetrahedron, 3, D::Affine, 4, 6, 8},
    {CellType::Tetrahedron, 2, D::CutCell, 4, 4, 6}, {CellType::Hexahedron, 1, D::Cell, 2, 2, 4},
    {CellType::Hexahedron, 1, D::Affine, 2, 2, 4},   {CellType::Hexahedron, 2, D::Cell, 4, 4, 6},
    {CellType::Hexahedron, 1, D::CutCell, 4, 6, 4},  {CellType::Hexahedron, 2, D::CutCell, 6, 8, 6},
};

TEST(QuadratureDegrees, PinnedForEveryCellOrderAndDomain) {
  for (const Pinned& p : kPinned) {
    const QuadratureDegrees q = default_quadrature_degrees(p.cell, p.order, p.domain);
    EXPECT_EQ(q.stiffness, p.stiffness) << name(p.cell) << " order " << p.order << " domain " << int(p.domain);
    EXPECT_EQ(q.mass, p.mass) << name(p.cell) << " order " << p.order << " domain " << int(p.domain);
    EXPECT_EQ(q.load, p.load) << name(p.cell) << " order " << p.order << " domain " << int(p.domain);
  }
  EXPECT_EQ(highest_total_degree(CellType::Hexahedron, 1), 3);
  EXPECT_EQ(highest_total_degree(CellType::Hexahedron, 2), 4);
  EXPECT_EQ(highest_total_degree(CellType::Tetrahedron, 3), 3);
}

TEST(QuadratureDegrees, RefusesOrdersTheCellDoesNotSupport) {
  EXPECT_THROW(default_quadrature_degrees(CellType::Hexahedron, 3), std::invalid_argument);
  EXPECT_THROW(default_quadrature_degrees(CellType::Tetrahedron, 0), std::invalid_argument);
}

// The assembler without a given degree and the manufactured-solution problem
// ask the one function: the general rule for the assembler (scene meshes may be
// curved, and it does not know the material), the affine constant-tangent rule
// for linear elasticity on the cube, the general one for the nonlinear materials.
TEST(QuadratureDegrees, AssemblerAndManufacturedProblemAskTheFunction) {
  for (int order : {1, 2, 3}) {
    const Mesh mesh = box_mesh(unit_cube(1), CellType::Tetrahedron, order);
    const DofMap dofs(mesh.num_nodes(), {});
    const Assembler a(mesh, dofs, -1);
    EXPECT_EQ(a.quadrature_degree(), 2 * order) << "order " << order;
    // Members set one by one: a designated initialiser would leave the later
    // members to -Wmissing-field-initializers.
    MmsCase linear;
    linear.problem = "linear";
    linear.cell = CellType::Tetrahedron;
    linear.order = order;
    linear.n = 1;
    EXPECT_EQ(MmsProblem(linear).options.quadrature_degree, order == 1 ? 1 : 2 * (order - 1)) << "order " << order;
    EXPECT_EQ(MmsProblem(linear).options.load_degree, 2 * order + 2) << "order " << order;
    MmsCase neo = linear;
    neo.problem = "neohookean";
    EXPECT_EQ(MmsProblem(neo).options.quadrature_degree, 2 * order) << "order " << order;
  }
}

TEST(ElementOrders, OneRuleForEveryCell) {
  EXPECT_TRUE(supports_order(CellType::Hexahedron, 1));
  EXPECT_TRUE(supports_order(CellType::Hexahedron, 2));
  EXPECT_FALSE(supports_order(CellType::Hexahedron, 3));
  EXPECT_FALSE(supports_order(CellType::Tetrahedron, 0));
  EXPECT_TRUE(supports_order(CellType::Tetrahedron, 7));
  EXPECT_FALSE(supports_order(CellType::Quadrilateral, 1));
  EXPECT_EQ(element_family_name(CellType::Tetrahedron, 2), "Tet10");
  EXPECT_EQ(element_family_name(CellType::Tetrahedron, 3), "Tet20");
  EXPECT_EQ(element_family_name(CellType::Hexahedron, 2), "Hex20");
  EXPECT_THROW(element_family_name(CellType::Hexahedron, 3), std::invalid_argument);
}

}  // namespace
}  // namespace hofem
