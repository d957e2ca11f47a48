#pragma once
// Energy, gradient (internal forces) and Hessian of one isoparametric element of
// a hyperelastic body (thesis §4.2–4.3, appendix 6.4), by quadrature.
//
// With reference nodes X (3 x n), current nodes x (3 x n) and reference
// gradients dN/dxi tabulated at the rule's points:
//   J = X dN/dxi,  dN/dX = dN/dxi J^-1,  F = x dN/dX = sum_i x_i (grad N_i)^T   (thesis §4.2.2)
//   E_e = sum_q w_q |det J_q| psi(F_q)
//   g_i = sum_q w_q |det J_q| P(F_q) grad N_i
//   H_ij(a,b) = sum_q w_q |det J_q| sum_{c,d} dP_ac/dF_bd  dN_i/dX_c  dN_j/dX_d
// N is the node count as a compile-time constant (4, 8, 10, 20) or Eigen::Dynamic
// for higher orders; all per-element storage is fixed-size for the former, and
// allocated once per workspace for the latter, so the element loop never allocates.
#include "basis/basis_tabulation.hpp"
#include "material/material.hpp"

#include <Eigen/Core>
#include <Eigen/LU>

#include <cmath>
#include <stdexcept>

namespace hofem {

/// Thrown when an element's isoparametric map is inverted or degenerate at a
/// quadrature point (det J <= 0 in the reference configuration).
class ElementGeometryError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

template <int N>
struct ElementWorkspace {
  static constexpr int D = N == Eigen::Dynamic ? Eigen::Dynamic : 3 * N;
  using Nodes = Eigen::Matrix<double, 3, N>;
  using Grad = Eigen::Matrix<double, N, 3>;
  using Vec = Eigen::Matrix<double, D, 1>;
  using Mat = Eigen::Matrix<double, D, D>;

  Nodes X, x;
  Grad dNdX;
  Vec g;
  Mat H;
  Eigen::Matrix<double, 9, 3> AD;  // dP/dF contracted with one gradient

  explicit ElementWorkspace(int n = N) {
    if constexpr (N == Eigen::Dynamic) {
      X.resize(3, n);
      x.resize(3, n);
      dNdX.resize(n, 3);
      g.resize(3 * n);
      H.resize(3 * n, 3 * n);
    }
    (void)n;
  }
  int nodes() const { return static_cast<int>(X.cols()); }
};

/// dN/dX and w |det J| at quadrature point q; throws ElementGeometryError if det J <= 0.
template <int N>
double reference_gradients(const BasisTabulation& tab, const Eigen::VectorXd& weights, int q, ElementWorkspace<N>& ws) {
  // n x 3, as a fixed-size map where n is a compile-time constant: Eigen then
  // inlines the small products instead of calling its general GEMM.
  const Eigen::Map<const typename ElementWorkspace<N>::Grad> dNdxi(tab.gradients.data() + 3 * q * tab.gradients.rows(),
                                                                   tab.gradients.rows(), 3);
  const Eigen::Matrix3d J = ws.X * dNdxi;
  const double det = J.determinant();
  if (!(det > 0.0)) throw ElementGeometryError("inverted or degenerate element (det J = " + std::to_string(det) + ")");
  ws.dNdX.noalias() = dNdxi * J.inverse();
  return weights[q] * det;
}

template <int N>
double element_energy(const Material& mat, const BasisTabulation& tab, const Eigen::VectorXd& w, ElementWorkspace<N>& ws) {
  double e = 0.0;
  for (int q = 0; q < tab.num_points; ++q) {
    const double wq = reference_gradients(tab, w, q, ws);
    const Mat3 F = ws.x * ws.dNdX;
    e += wq * mat.energy(F);
  }
  return e;
}

/// Fills ws.g; returns the element energy.
template <int N>
double element_gradient(const Material& mat, const BasisTabulation& tab, const Eigen::VectorXd& w, ElementWorkspace<N>& ws) {
  ws.g.setZero();
  double e = 0.0;
  const int n = ws.nodes();
  for (int q = 0; q < tab.num_points; ++q) {
    const double wq = reference_gradients(tab, w, q, ws);
    const Mat3 F = ws.x * ws.dNdX;
    Mat3 P;
    e += wq * mat.evaluate(F, &P, nullptr);  // one call: psi and P share their work (SVD, cofactor)
    for (int i = 0; i < n; ++i) ws.g.template segment<3>(3 * i).noalias() += wq * P * ws.dNdX.row(i).transpose();
  }
  return e;
}

/// Fills ws.g and ws.H (full symmetric); returns the element energy. With
/// project_psd, dP/dF is projected to positive semi-definite at each point.
template <int N>
double element_hessian(const Material& mat, const BasisTabulation& tab, const Eigen::VectorXd& w, ElementWorkspace<N>& ws,
                       bool project_psd_at_points) {
  ws.g.setZero();
  ws.H.setZero();
  double e = 0.0;
  const int n = ws.nodes();
  for (int q = 0; q < tab.num_points; ++q) {
    const double wq = reference_gradients(tab, w, q, ws);
    const Mat3 F = ws.x * ws.dNdX;
    Mat3 P;
    Mat9 A;
    e += wq * mat.evaluate(F, &P, &A);  // psi, P and dP/dF from one evaluation
    if (project_psd_at_points) A = project_psd(A);
    for (int j = 0; j < n; ++j) {
      ws.g.template segment<3>(3 * j).noalias() += wq * P * ws.dNdX.row(j).transpose();
      // AD(:, b) = sum_d A(:, b + 3d) dN_j/dX_d
      ws.AD.noalias() = ws.dNdX(j, 0) * A.template middleCols<3>(0) + ws.dNdX(j, 1) * A.template middleCols<3>(3) +
                        ws.dNdX(j, 2) * A.template middleCols<3>(6);
      for (int i = 0; i <= j; ++i) {
        // H_ij(a, b) = sum_c dN_i/dX_c AD(a + 3c, b)
        const Eigen::Matrix3d Hij = wq * (ws.dNdX(i, 0) * ws.AD.template topRows<3>() +
                                          ws.dNdX(i, 1) * ws.AD.template middleRows<3>(3) +
                                          ws.dNdX(i, 2) * ws.AD.template bottomRows<3>());
        ws.H.template block<3, 3>(3 * i, 3 * j) += Hij;
      }
    }
  }
  // Mirror the upper block triangle (the element Hessian is symmetric: A has major symmetry).
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < j; ++i) ws.H.template block<3, 3>(3 * j, 3 * i) = ws.H.template block<3, 3>(3 * i, 3 * j).transpose();
  return e;
}

}  // namespace hofem
