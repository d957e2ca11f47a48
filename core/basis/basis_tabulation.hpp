#pragma once
// Values and reference gradients of a basis at every point of a quadrature rule,
// computed once and reused by every element that shares (basis, rule).
#include "basis/reference_basis.hpp"
#include "quadrature/quadrature_rule.hpp"

#include <Eigen/Core>

namespace hofem {

struct BasisTabulation {
  int num_points = 0;
  int num_basis = 0;
  int dim = 0;
  Eigen::MatrixXd values;     ///< num_basis x num_points: column q holds N(x_q)
  Eigen::MatrixXd gradients;  ///< num_basis x (dim * num_points): columns [dim q, dim q + dim) hold dN/dxi at x_q

  /// num_basis x dim block of reference gradients at point q.
  auto gradient(int q) const { return gradients.middleCols(static_cast<Eigen::Index>(dim) * q, dim); }
};

/// Tabulates `basis` over `rule` (cells must match).
BasisTabulation tabulate(const ReferenceBasis& basis, const QuadratureRule& rule);

/// A quadrature rule of one element with the basis tabulated on it: the finite
/// cell method gives every cut cell its own rule (Longva et al. 2020 §4.4-4.5).
struct ElementQuadrature {
  QuadratureRule rule;
  BasisTabulation tabulation;
};

/// lagrange_basis(cell, order) tabulated on the given reference points (dim x n)
/// and weights. An empty rule is allowed (an element that contributes nothing).
ElementQuadrature make_element_quadrature(CellType cell, int order, Eigen::MatrixXd points, Eigen::VectorXd weights);

/// Cached tabulation of lagrange_basis(cell, order) over quadrature_rule(cell, degree):
/// built on first use, then shared (thread-safe; the reference stays valid).
const BasisTabulation& cached_tabulation(CellType cell, int order, int quadrature_degree);

/// Drops every cached tabulation, invalidating the references handed out: only
/// for timing a run from a cold start (benchmarks), when nothing refers to one.
void clear_tabulation_cache();

}  // namespace hofem
