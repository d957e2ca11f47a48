#include "study/field_error.hpp"

#include "basis/basis_tabulation.hpp"
#include "basis/reference_basis.hpp"
#include "quadrature/rule_library.hpp"

#include <Eigen/LU>
#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace hofem {

namespace {

// Visits every point of the body: f(element, tabulation, point index in the
// rule, running index, reference weight).
template <class F>
void for_each_point(const Mesh& mesh, int degree, const std::vector<std::shared_ptr<const ElementQuadrature>>& own,
                    F&& f) {
  const BasisTabulation& standard = cached_tabulation(mesh.cell, mesh.order, degree);
  const QuadratureRule& standard_rule = quadrature_rule(mesh.cell, degree);
  long long k = 0;
  for (int e = 0; e < mesh.num_elements(); ++e) {
    const bool mine = !own.empty() && own[e];
    const BasisTabulation& tab = mine ? own[e]->tabulation : standard;
    const Eigen::VectorXd& weights = mine ? own[e]->rule.weights : standard_rule.weights;
    for (int p = 0; p < tab.num_points; ++p, ++k) f(e, tab, p, k, weights[p]);
  }
}

}  // namespace

BodyQuadrature body_quadrature(const Mesh& mesh, int degree,
                               const std::vector<std::shared_ptr<const ElementQuadrature>>& own_rules) {
  const int ne = mesh.num_elements();
  if (!own_rules.empty() && static_cast<int>(own_rules.size()) != ne)
    throw std::invalid_argument(fmt::format("body_quadrature: {} rules for {} elements", own_rules.size(), ne));
  long long n = 0;
  for_each_point(mesh, degree, own_rules, [&](int, const BasisTabulation&, int, long long, double) { ++n; });
  BodyQuadrature q;
  q.degree = degree;
  q.own_rules = own_rules;
  q.X.resize(3, n);
  q.w.resize(n);
  q.at.element.resize(n);
  q.at.xi.resize(3, n);
  q.at.extrapolated.assign(n, 0);
  q.J_inverse.resize(n);
  const Eigen::MatrixXd& ref_nodes = lagrange_basis(mesh.cell, mesh.order).nodes();
  for_each_point(mesh, degree, own_rules, [&](int e, const BasisTabulation& tab, int p, long long k, double w) {
    Eigen::Vector3d X = Eigen::Vector3d::Zero(), xi = Eigen::Vector3d::Zero();
    Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
    for (int i = 0; i < tab.num_basis; ++i) {
      const Eigen::Vector3d Xi = mesh.nodes.col(mesh.elements(i, e));
      X += tab.values(i, p) * Xi;
      J += Xi * tab.gradient(p).row(i);
      xi += tab.values(i, p) * ref_nodes.col(i);  // the basis reproduces linear functions of xi
    }
    q.X.col(k) = X;
    q.w[k] = w * std::abs(J.determinant());
    q.J_inverse[k] = J.inverse();
    q.at.element[k] = e;
    q.at.xi.col(k) = xi;
  });
  return q;
}

PointValues BodyQuadrature::values(const Mesh& mesh, const Eigen::VectorXd& u) const {
  PointValues out;
  out.value.resize(3, w.size());
  out.gradient.resize(w.size());
  for_each_point(mesh, degree, own_rules, [&](int e, const BasisTabulation& tab, int p, long long k, double) {
    Eigen::Vector3d v = Eigen::Vector3d::Zero();
    Eigen::Matrix3d G = Eigen::Matrix3d::Zero();
    for (int i = 0; i < tab.num_basis; ++i) {
      const int node = mesh.elements(i, e);
      v += tab.values(i, p) * u.segment<3>(3 * node);
      G += u.segment<3>(3 * node) * tab.gradient(p).row(i);
    }
    out.value.col(k) = v;
    out.gradient[k] = G * J_inverse[k];
  });
  return out;
}

double FieldError::rms() const { return volume > 0 ? std::sqrt(l2 * l2 / volume) : 0.0; }

FieldError field_error(const BodyQuadrature& q, const PointValues& ref, const Mesh& run_mesh,
                       const EmbeddedPointMap& run_points, const Eigen::VectorXd& u_run) {
  if (run_points.size() != q.at.size() || ref.value.cols() != q.at.size() ||
      static_cast<int>(ref.gradient.size()) != q.at.size())
    throw std::invalid_argument(fmt::format("field_error: {} located points and {} reference values for {} quadrature "
                                            "points",
                                            run_points.size(), ref.value.cols(), q.at.size()));
  const PointValues run = evaluate_at_points(run_mesh, run_points, u_run, true);
  FieldError e;
  double l2 = 0, h1 = 0, rl2 = 0, rh1 = 0;
  for (int p = 0; p < q.at.size(); ++p) {
    const double w = q.w[p];
    const double d2 = (run.value.col(p) - ref.value.col(p)).squaredNorm();
    l2 += w * d2;
    h1 += w * (run.gradient[p] - ref.gradient[p]).squaredNorm();
    rl2 += w * ref.value.col(p).squaredNorm();
    rh1 += w * ref.gradient[p].squaredNorm();
    e.max_pointwise = std::max(e.max_pointwise, std::sqrt(d2));
    e.volume += w;
    if (run_points.extrapolated[p]) e.extrapolated_volume += w;
  }
  e.l2 = std::sqrt(l2);
  e.h1 = std::sqrt(h1);
  e.reference_l2 = std::sqrt(rl2);
  e.reference_h1 = std::sqrt(rh1);
  return e;
}

}  // namespace hofem
