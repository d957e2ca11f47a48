#include "basis/simplex_lagrange_basis.hpp"

#include "basis/lagrange_nodes.hpp"

#include <Eigen/LU>
#include <Eigen/SVD>
#include <fmt/format.h>

#include <cmath>

namespace hofem {

namespace {

double condition_number(const Eigen::MatrixXd& A) {
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(A);
  const auto& s = svd.singularValues();
  return s(0) / s(s.size() - 1);
}

}  // namespace

SimplexLagrangeBasis::SimplexLagrangeBasis(CellType cell, int order)
    : cell_(cell), order_(order), psi_(cell, order) {
  nodes_ = simplex_lagrange_nodes(cell, order);
  const int n = static_cast<int>(nodes_.cols());
  if (n != psi_.size())
    throw std::logic_error(fmt::format("SimplexLagrangeBasis: {} nodes for {} polynomials", n, psi_.size()));
  Eigen::MatrixXd V(n, n);
  Eigen::VectorXd row(n);
  for (int i = 0; i < n; ++i) {
    psi_.evaluate(nodes_.col(i).data(), row.data(), nullptr);
    V.row(i) = row.transpose();
  }
  coefficients_ = V.partialPivLu().inverse();
  vandermonde_ = std::move(V);
}

double SimplexLagrangeBasis::vandermonde_condition() const { return condition_number(vandermonde_); }

std::string SimplexLagrangeBasis::element_name() const {
  const char* stem = cell_ == CellType::Segment ? "Line" : cell_ == CellType::Triangle ? "Tri" : "Tet";
  return fmt::format("{}{}", stem, size());
}

std::vector<std::array<int, 3>> SimplexLagrangeBasis::polynomial_space() const {
  return total_degree_exponents(dim(), order_);
}

void SimplexLagrangeBasis::evaluate(const Eigen::Ref<const Eigen::VectorXd>& xi,
                                    Eigen::Ref<Eigen::VectorXd> values) const {
  Eigen::VectorXd p(psi_.size());
  psi_.evaluate(xi.data(), p.data(), nullptr);
  values.noalias() = coefficients_.transpose() * p;
}

void SimplexLagrangeBasis::gradients(const Eigen::Ref<const Eigen::VectorXd>& xi,
                                     Eigen::Ref<Eigen::MatrixXd> grads) const {
  const int d = dim();
  Eigen::VectorXd p(psi_.size());
  // Row-major (m, c) layout from psi_.evaluate maps to a size x dim matrix.
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> dp(psi_.size(), d);
  psi_.evaluate(xi.data(), p.data(), dp.data());
  grads.noalias() = coefficients_.transpose() * dp;
}

double monomial_vandermonde_condition(CellType cell, int order) {
  const Eigen::MatrixXd x = simplex_lagrange_nodes(cell, order);
  const auto exps = total_degree_exponents(dimension(cell), order);
  const int n = static_cast<int>(x.cols());
  Eigen::MatrixXd V(n, n);
  for (int i = 0; i < n; ++i)
    for (int m = 0; m < n; ++m) {
      double v = 1.0;
      for (int c = 0; c < x.rows(); ++c) v *= std::pow(x(c, i), exps[m][c]);
      V(i, m) = v;
    }
  return condition_number(V);
}

}  // namespace hofem
