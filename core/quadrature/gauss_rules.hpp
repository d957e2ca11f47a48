#pragma once
// Gauss-type rules of any size: 1D Gauss–Legendre, tensor products on the quad
// and hex, and collapsed (Stroud conical product) rules on the triangle and tet.
#include "quadrature/quadrature_rule.hpp"

namespace hofem {

/// Points per direction for a Gauss rule exact to total/per-direction degree p:
/// n points integrate degree 2n - 1 exactly, so n = ceil((p + 1) / 2).
int gauss_points_for_degree(int degree);

/// n-point Gauss–Legendre rule on [-1, 1] (degree 2n - 1), nodes ascending.
QuadratureRule gauss_legendre(int n);

/// n-point Gauss–Jacobi rule on [-1, 1] for the weight (1 - x)^alpha (returned as
/// a segment rule; the weight function is *not* included in `integrate`).
QuadratureRule gauss_jacobi(int n, int alpha);

/// Tensor-product Gauss–Legendre rule on [-1, 1]^d with n points per direction
/// (cell = Quadrilateral or Hexahedron; Segment gives gauss_legendre(n)).
QuadratureRule gauss_tensor(CellType cell, int n);

/// Collapsed Gauss rule on the unit triangle or tetrahedron exact to at least `degree`
/// (Stroud 1971, conical product): the square/cube [0,1]^d is collapsed onto the
/// simplex by x = u(1-v)(1-w), y = v(1-w), z = w, whose Jacobian (1-v)(1-w)^2 is
/// absorbed into Gauss–Jacobi weights (alpha = 1 in v, alpha = 2 in w). Its true
/// degree is 2n - 1 with n = gauss_points_for_degree(degree); that is what it reports.
QuadratureRule gauss_collapsed(CellType cell, int degree);

/// Degree-p rule of the cheapest Gauss type on any cell (tensor or collapsed).
QuadratureRule gauss_rule_for_degree(CellType cell, int degree);

}  // namespace hofem
