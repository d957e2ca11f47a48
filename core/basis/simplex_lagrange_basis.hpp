#pragma once
// Lagrange basis of any order on the segment, triangle or tetrahedron, on
// equispaced nodes in Gmsh order.
//
// Thesis §4.1.2 builds N from the Vandermonde system A^T N = (1, x, y, ..., y^n)^T
// over monomials (eq. 4.28, 4.34). We solve the same system over the orthonormal
// Dubiner basis psi instead: with V_ij = psi_j(x_i), N(x) = V^{-T} psi(x). The
// interpolation space is the same (P_p), but cond(V) stays small enough for
// order 6 and beyond to keep the Kronecker property to ~1e-13, where the monomial
// Vandermonde loses several more digits (measured in the verification report).
#include "basis/reference_basis.hpp"
#include "basis/simplex_orthonormal_basis.hpp"

namespace hofem {

class SimplexLagrangeBasis final : public ReferenceBasis {
 public:
  SimplexLagrangeBasis(CellType cell, int order);

  CellType cell() const override { return cell_; }
  int order() const override { return order_; }
  std::string element_name() const override;
  std::vector<std::array<int, 3>> polynomial_space() const override;

  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& xi, Eigen::Ref<Eigen::VectorXd> values) const override;
  void gradients(const Eigen::Ref<const Eigen::VectorXd>& xi, Eigen::Ref<Eigen::MatrixXd> grads) const override;

  /// 2-norm condition number of the Vandermonde matrix V (orthonormal basis);
  /// computed on request (an SVD), not when the basis is built.
  double vandermonde_condition() const;

 private:
  CellType cell_;
  int order_;
  OrthonormalSimplexBasis psi_;
  Eigen::MatrixXd coefficients_;  // C = V^{-1}: N_i = sum_m C(m, i) psi_m
  Eigen::MatrixXd vandermonde_;   // kept for vandermonde_condition()
};

/// 2-norm condition number of the *monomial* Vandermonde matrix of the thesis
/// (eq. 4.28/4.34) on the same nodes, for comparison.
double monomial_vandermonde_condition(CellType cell, int order);

}  // namespace hofem
