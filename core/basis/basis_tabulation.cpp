#include "basis/basis_tabulation.hpp"

#include "quadrature/rule_library.hpp"

#include <fmt/format.h>

#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <tuple>

namespace hofem {

BasisTabulation tabulate(const ReferenceBasis& basis, const QuadratureRule& rule) {
  if (basis.cell() != rule.cell)
    throw std::invalid_argument(fmt::format("tabulate: basis on {} but rule on {}", name(basis.cell()), name(rule.cell)));
  BasisTabulation t;
  t.num_points = rule.size();
  t.num_basis = basis.size();
  t.dim = basis.dim();
  t.values.resize(t.num_basis, t.num_points);
  t.gradients.resize(t.num_basis, static_cast<Eigen::Index>(t.dim) * t.num_points);
  for (int q = 0; q < t.num_points; ++q) {
    basis.evaluate(rule.points.col(q), t.values.col(q));
    basis.gradients(rule.points.col(q), t.gradients.middleCols(static_cast<Eigen::Index>(t.dim) * q, t.dim));
  }
  return t;
}

namespace {
std::mutex& tabulation_mutex() {
  static std::mutex mutex;
  return mutex;
}
std::map<std::tuple<int, int, int>, std::unique_ptr<BasisTabulation>>& tabulation_cache() {
  static std::map<std::tuple<int, int, int>, std::unique_ptr<BasisTabulation>> cache;
  return cache;
}
}  // namespace

const BasisTabulation& cached_tabulation(CellType cell, int order, int quadrature_degree) {
  const ReferenceBasis& basis = lagrange_basis(cell, order);
  const QuadratureRule& rule = quadrature_rule(cell, quadrature_degree);
  std::lock_guard<std::mutex> lock(tabulation_mutex());
  auto& slot = tabulation_cache()[{static_cast<int>(cell), order, quadrature_degree}];
  if (!slot) slot = std::make_unique<BasisTabulation>(tabulate(basis, rule));
  return *slot;
}

void clear_tabulation_cache() {
  std::lock_guard<std::mutex> lock(tabulation_mutex());
  tabulation_cache().clear();
}

ElementQuadrature make_element_quadrature(CellType cell, int order, Eigen::MatrixXd points, Eigen::VectorXd weights) {
  if (points.rows() != dimension(cell) || points.cols() != weights.size())
    throw std::invalid_argument("make_element_quadrature: points must be dim x n with n weights");
  ElementQuadrature q;
  q.rule.cell = cell;
  q.rule.id = "element";
  q.rule.source = "per-element rule (finite cell method)";
  q.rule.points = std::move(points);
  q.rule.weights = std::move(weights);
  q.tabulation = tabulate(lagrange_basis(cell, order), q.rule);  // no points: sizes only
  return q;
}

}  // namespace hofem
