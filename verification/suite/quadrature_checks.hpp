#pragma once
#include "report.hpp"

#include "quadrature/quadrature_rule.hpp"

namespace hofem::verification {

/// Largest error over all monomials of total degree <= rule.degree, each relative
/// to the integral of |monomial| (so odd monomials on [-1,1]^d, whose integral is
/// zero, are measured on the same scale as the others).
double max_monomial_error(const QuadratureRule& rule, int max_degree);

/// Largest |Q(psi)| / sqrt(|cell|) over orthonormal polynomials psi of total
/// degree exactly `degree` (their exact integral is 0). Measures whether a rule
/// fails at a degree on an O(1) scale: monomials cannot, because a Gauss rule's
/// error on x^(2n) decays like 4^-n and vanishes below double rounding for n > 20.
double orthonormal_error(const QuadratureRule& rule, int degree);

/// The checks of one rule: exactness to its degree, failure at degree + 1,
/// weight sum, and the positivity / interiority its source claims.
void check_rule(Report& report, const QuadratureRule& rule);

/// Every quadrature check: Gauss–Legendre 1..64 (exactness and ulp accuracy
/// against a __float128 computation), tensor rules, collapsed rules to degree 30,
/// every tabulated rule, and the rule query for degrees 1..30.
void add_quadrature_checks(Report& report);

}  // namespace hofem::verification
