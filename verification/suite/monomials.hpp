#pragma once
// Exact integrals of monomials over the reference cells, the ground truth of the
// quadrature checks.
#include "quadrature/cell_type.hpp"

#include <array>
#include <vector>

namespace hofem::verification {

using Exponent = std::array<int, 3>;

/// All exponents (a, b, c) of the cell's dimension with a + b + c == degree.
std::vector<Exponent> monomials_of_degree(int dim, int degree);

/// Exact integral of x^a y^b z^c over the reference cell:
///  unit simplex: a! b! c! / (a + b + c + d)!  (d = dimension);
///  [-1,1]^d:     prod_i (1 + (-1)^e_i) / (e_i + 1).
/// Computed in long double, so the value is correct to well below double rounding.
long double exact_monomial_integral(CellType cell, const Exponent& e);

/// Integral of |x^a y^b z^c| (equals the integral on simplices), the scale of a
/// monomial's quadrature error.
long double abs_monomial_integral(CellType cell, const Exponent& e);

/// x^a y^b z^c at a point.
double monomial(const double* x, int dim, const Exponent& e);

}  // namespace hofem::verification
