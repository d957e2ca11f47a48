#pragma once
// The default degrees of the quadrature rules that integrate an element's
// terms, in one place: the assembler, the manufactured-solution problem, the
// finite cell rules, the consistent mass and the body-force loads ask this.
// What "degree" means follows the rules that use it: on simplices and on cut
// cells (moment-fitted rules) the total degree of the polynomials integrated
// exactly, on uncut hexahedra the degree per direction of the tensor Gauss rule.
//
//   stiffness  dN_i/dX . C . dN_j/dX on an affine cell:
//              - tet of order p, constant tangent (linear elasticity): the
//                product of two gradients of degree p - 1, i.e. 2(p - 1)
//                (at least 1) integrates it exactly;
//              - otherwise 2p: the tangent varies with the solution (F has
//                degree p - 1 per entry, and the material is nonlinear in
//                it), or the cell is curved (the Jacobian is not constant), so
//                no degree is exact; 2p is the thesis' choice for Tet10 (§3.3)
//                and keeps the rule's error below the discretisation's at the
//                rates verification/suite measures;
//              - uncut hexahedra: 2p per direction (p + 1 Gauss points), exact
//                for the trilinear / serendipity gradients' products;
//              - cut cells: 2 (d - 1) in total degree, d the basis' highest
//                total degree (Hex8 xyz: 3, Hex20 x^2yz: 4; Tet p: p), the
//                product of two gradients; tets 2p as uncut ones (Longva et
//                al. 2020 §4.5 integrate cut Hex20 at degree 4 after their LP
//                simplification; hofem keeps the full product degree, 6).
//   mass       N_i N_j: 2p (2d on cut cells).
//   load       N_i f(X): 2p + 2, two degrees above the basis for a smooth f.
#include "quadrature/cell_type.hpp"

namespace hofem {

struct QuadratureDegrees {
  int stiffness = 0;
  int mass = 0;
  int load = 0;
};

/// Where an element's terms are integrated.
enum class IntegrationDomain {
  Cell,     ///< the whole element, curved or not: the general rule
  Affine,   ///< an affine element with a constant material tangent (linear elasticity)
  CutCell,  ///< a finite cell's part of an affine background cell (moment-fitted rules)
};

QuadratureDegrees default_quadrature_degrees(CellType cell, int order, IntegrationDomain domain = IntegrationDomain::Cell);

/// The highest total degree of a monomial in the order-p Lagrange space of the
/// cell: p on simplices, 3 for Hex8 (xyz), 4 for the serendipity Hex20 (x^2yz).
int highest_total_degree(CellType cell, int order);

}  // namespace hofem
