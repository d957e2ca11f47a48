#pragma once
// Orthonormal polynomial bases of total degree <= p on the reference segment,
// triangle and tetrahedron: Legendre on [-1, 1] and the Dubiner / PKDO bases
// (Dubiner 1991; Karniadakis & Sherwin, "Spectral/hp element methods", §3.2) on
// the unit simplex. They replace the monomials of the thesis' Vandermonde system
// (eq. 4.28 / 4.34): the same interpolation space, but a Vandermonde matrix whose
// condition number grows slowly with the order instead of exponentially.
//
// Evaluation avoids the collapsed coordinates' division by zero at the top
// vertex: every factor P_i(a) ((1-b)/2)^i is computed by a *homogenised*
// recurrence whose coefficients are polynomials in the simplex coordinates, so
// values and gradients are smooth and exact everywhere on the closed simplex.
#include "quadrature/cell_type.hpp"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace hofem {

/// Exponents (a, b, c) of the monomials of total degree <= p in dim (1 to 3)
/// variables (the unused ones 0), a outermost, then b, then c: also the order of
/// the orthonormal basis functions' indices (i, j, k) below.
std::vector<std::array<int, 3>> total_degree_exponents(int dim, int p);

class OrthonormalSimplexBasis {
 public:
  /// cell: Segment ([-1,1]), Triangle or Tetrahedron (unit simplex); order >= 0.
  OrthonormalSimplexBasis(CellType cell, int order);

  CellType cell() const { return cell_; }
  int order() const { return order_; }
  int size() const { return static_cast<int>(index_.size()); }
  /// Total degree of basis function m.
  int degree_of(int m) const { return index_[m][0] + index_[m][1] + index_[m][2]; }

  /// values[m] = psi_m(x); if gradients != nullptr, gradients[m*dim + c] = d psi_m / d x_c.
  void evaluate(const double* x, double* values, double* gradients) const;

 private:
  void evaluate_unscaled(const double* x, double* values, double* gradients) const;

  CellType cell_;
  int order_;
  int dim_;
  std::vector<std::array<int, 3>> index_;  // (i, j, k) of each basis function
  std::vector<double> scale_;              // 1 / ||psi_m||, computed with an exact Gauss rule
};

}  // namespace hofem
