#pragma once
// Hex8 (trilinear) and Hex20 (quadratic serendipity) bases on [-1,1]^3, Gmsh node order.
#include "basis/reference_basis.hpp"

namespace hofem {

class Hex8Basis final : public ReferenceBasis {
 public:
  Hex8Basis();
  CellType cell() const override { return CellType::Hexahedron; }
  int order() const override { return 1; }
  std::string element_name() const override { return "Hex8"; }
  /// Q1: exponents in {0,1}^3 (includes xy, yz, xz, xyz).
  std::vector<std::array<int, 3>> polynomial_space() const override;
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& xi, Eigen::Ref<Eigen::VectorXd> values) const override;
  void gradients(const Eigen::Ref<const Eigen::VectorXd>& xi, Eigen::Ref<Eigen::MatrixXd> grads) const override;
};

/// 20-node serendipity hexahedron: corners
///   N = (1+x xa)(1+y ya)(1+z za)(x xa + y ya + z za - 2)/8,
/// edge midpoints (coordinate d of the node is 0)
///   N = (1 - x_d^2) prod_{c != d} (1 + x_c xa_c)/4
/// (Zienkiewicz & Taylor, The Finite Element Method, Vol. 1, §6.5).
class Hex20Basis final : public ReferenceBasis {
 public:
  Hex20Basis();
  CellType cell() const override { return CellType::Hexahedron; }
  int order() const override { return 2; }
  std::string element_name() const override { return "Hex20"; }
  /// Serendipity S_2: monomials with at most one exponent 2, the others <= 1 (20 of them).
  std::vector<std::array<int, 3>> polynomial_space() const override;
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& xi, Eigen::Ref<Eigen::VectorXd> values) const override;
  void gradients(const Eigen::Ref<const Eigen::VectorXd>& xi, Eigen::Ref<Eigen::MatrixXd> grads) const override;
};

}  // namespace hofem
