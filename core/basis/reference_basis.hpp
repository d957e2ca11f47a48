#pragma once
// Nodal finite element bases on a reference cell: values and reference gradients
// at arbitrary points. Concrete bases: SimplexLagrangeBasis (segment, triangle,
// tetrahedron, any order) and Hex8Basis / Hex20Basis.
#include "quadrature/cell_type.hpp"

#include <Eigen/Core>

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace hofem {

class ReferenceBasis {
 public:
  virtual ~ReferenceBasis() = default;

  virtual CellType cell() const = 0;
  /// Highest total degree k such that every polynomial of degree <= k is reproduced.
  virtual int order() const = 0;
  /// Gmsh-style element name, e.g. "Tet10", "Tri6", "Hex20", "Line3".
  virtual std::string element_name() const = 0;
  /// Exponents (a, b, c) of monomials spanning exactly the basis' polynomial space
  /// (P_p on simplices, Q_1 for Hex8, the 20-dimensional serendipity space for Hex20).
  virtual std::vector<std::array<int, 3>> polynomial_space() const = 0;

  int dim() const { return dimension(cell()); }
  int size() const { return static_cast<int>(nodes_.cols()); }
  /// Node coordinates, dim x size, in Gmsh order: N_i(nodes.col(j)) = delta_ij.
  const Eigen::MatrixXd& nodes() const { return nodes_; }

  /// values[i] = N_i(xi); values has size() entries.
  virtual void evaluate(const Eigen::Ref<const Eigen::VectorXd>& xi, Eigen::Ref<Eigen::VectorXd> values) const = 0;
  /// grads(i, c) = dN_i / dxi_c; grads is size() x dim().
  virtual void gradients(const Eigen::Ref<const Eigen::VectorXd>& xi, Eigen::Ref<Eigen::MatrixXd> grads) const = 0;

  Eigen::VectorXd evaluate(const Eigen::Ref<const Eigen::VectorXd>& xi) const {
    Eigen::VectorXd v(size());
    evaluate(xi, v);
    return v;
  }
  Eigen::MatrixXd gradients(const Eigen::Ref<const Eigen::VectorXd>& xi) const {
    Eigen::MatrixXd g(size(), dim());
    gradients(xi, g);
    return g;
  }

 protected:
  Eigen::MatrixXd nodes_;
};

/// A new Lagrange basis: simplices (segment, triangle, tet) of any order >= 1;
/// hex order 1 (Hex8) or 2 (Hex20 serendipity).
std::unique_ptr<ReferenceBasis> make_lagrange_basis(CellType cell, int order);

/// Shared, lazily built instance of make_lagrange_basis(cell, order) (thread-safe;
/// the reference stays valid for the program's life).
const ReferenceBasis& lagrange_basis(CellType cell, int order);

}  // namespace hofem
