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
#include "element/hessian_product.hpp"
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

  Nodes X, x;
  Grad dNdX;
  Grad Xt, xt, gt;  // element_hessian: X, x and the forces as rows (n x 3)
  Vec g;
  // element_hessian's operands over all quadrature points (sized on the first
  // element with more points than before: the element loop does not allocate):
  // E (ld x 3Q: the six blocks a <= b of w_q D_q A_q^{ab}, stacked, ld = 6n
  // rounded up to 8, padding rows zero), Gt (3Q x n: D_q^T stacked), Hs = E Gt.
  Eigen::MatrixXd E, Gt, Hs;

  explicit ElementWorkspace(int n = N) {
    if constexpr (N == Eigen::Dynamic) {
      X.resize(3, n);
      x.resize(3, n);
      dNdX.resize(n, 3);
      Xt.resize(n, 3);
      xt.resize(n, 3);
      gt.resize(n, 3);
      g.resize(3 * n);
    }
    (void)n;
  }
  int nodes() const { return static_cast<int>(X.cols()); }

  /// Entry (3i + a, 3j + b) of the element Hessian element_hessian() computed:
  /// H^{ab}_ij from block s(a, b) of Hs at (i, j) for a < b, from block s(b, a)
  /// at (j, i) for a > b, and from the upper triangle of block s(a, a) for a = b.
  /// Every entry and its mirror come from the same computed value: the element
  /// Hessian is exactly symmetric (CHOLMOD reads one triangle, the block
  /// products assume symmetry). Read directly by the scatter: no 3n x 3n copy.
  double hessian_entry(int i, int a, int j, int b) const {
    static constexpr int kBlock[3][3] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}};
    const int n = nodes();
    const bool upper = a < b || (a == b && i <= j);
    return upper ? Hs(kBlock[a][b] * n + i, j) : Hs(kBlock[a][b] * n + j, i);
  }
};

/// dN/dX (into dNdX) and w |det J| at quadrature point q from the reference node
/// coordinates as rows (Xt, n x 3); throws ElementGeometryError if det J <= 0.
/// J = X dN/dxi is formed as Xt^T dN/dxi: each entry a dot product of two
/// contiguous columns, which vectorises, where X's rows are strided.
template <int N>
double reference_gradients_from(const BasisTabulation& tab, const Eigen::VectorXd& weights, int q,
                                const typename ElementWorkspace<N>::Grad& Xt, typename ElementWorkspace<N>::Grad& dNdX) {
  // n x 3, as a fixed-size map where n is a compile-time constant: Eigen then
  // inlines the small products instead of calling its general GEMM.
  const Eigen::Map<const typename ElementWorkspace<N>::Grad> dNdxi(tab.gradients.data() + 3 * q * tab.gradients.rows(),
                                                                   tab.gradients.rows(), 3);
  // lazyProduct: Eigen sends products with rows + cols + depth >= 20 (Tet20,
  // Hex20: 3 + 3 + 20) to its general GEMM, ~10x slower at these sizes.
  const Eigen::Matrix3d J = Xt.transpose().lazyProduct(dNdxi);
  const double det = J.determinant();
  if (!(det > 0.0)) throw ElementGeometryError("inverted or degenerate element (det J = " + std::to_string(det) + ")");
  dNdX.noalias() = dNdxi.lazyProduct(J.inverse());
  return weights[q] * det;
}

/// dN/dX (into ws.dNdX) and w |det J| at quadrature point q; throws
/// ElementGeometryError if det J <= 0.
template <int N>
double reference_gradients(const BasisTabulation& tab, const Eigen::VectorXd& weights, int q, ElementWorkspace<N>& ws) {
  if constexpr (N == Eigen::Dynamic) {
    const Eigen::Map<const Eigen::MatrixXd> dNdxi(tab.gradients.data() + 3 * q * tab.gradients.rows(),
                                                  tab.gradients.rows(), 3);
    const Eigen::Matrix3d J = ws.X * dNdxi;
    const double det = J.determinant();
    if (!(det > 0.0)) throw ElementGeometryError("inverted or degenerate element (det J = " + std::to_string(det) + ")");
    ws.dNdX.noalias() = dNdxi * J.inverse();
    return weights[q] * det;
  } else {
    const typename ElementWorkspace<N>::Grad Xt = ws.X.transpose();
    return reference_gradients_from<N>(tab, weights, q, Xt, ws.dNdX);
  }
}

template <int N>
double element_energy(const Material& mat, const BasisTabulation& tab, const Eigen::VectorXd& w, ElementWorkspace<N>& ws) {
  double e = 0.0;
  for (int q = 0; q < tab.num_points; ++q) {
    const double wq = reference_gradients(tab, w, q, ws);
    const Mat3 F = ws.x.lazyProduct(ws.dNdX);
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
    const Mat3 F = ws.x.lazyProduct(ws.dNdX);
    Mat3 P;
    e += wq * mat.evaluate(F, &P, nullptr);  // one call: psi and P share their work (SVD, cofactor)
    for (int i = 0; i < n; ++i) ws.g.template segment<3>(3 * i).noalias() += wq * P * ws.dNdX.row(i).transpose();
  }
  return e;
}

/// The components (a, b), a <= b, of the element Hessian's 3x3 node blocks, in
/// the order element_hessian stacks them; the other three follow by symmetry.
inline constexpr int kHessianPairs[6][2] = {{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 2}};

/// Floating-point operations element_hessian executes per element, material
/// evaluation (dP/dF) not counted: per point, J and dN/dX (18n each + ~60 for the
/// 3x3 inverse), F (18n), the internal forces (18n), the six n x 3 by 3 x 3
/// products of E (108n); per element the product E Gt (2 x 6n x 3Q x n; the
/// padding rows of E, up to 7, are executed but not counted).
inline double element_hessian_flops(int n, int points) {
  return static_cast<double>(points) * (180.0 * n + 60.0 + 36.0 * n * n);
}

/// Fills ws.g and ws.Hs (the Hessian's entries: ws.hessian_entry); returns the element energy. With
/// project_psd, dP/dF is projected to positive semi-definite at each point.
///
/// Component block (a, b) of the Hessian, H^{ab}_ij = H(3i + a, 3j + b), is
///   H^{ab} = sum_q w_q D_q A_q^{ab} D_q^T,   A_q^{ab}(c, d) = dP_ac/dF_bd at q,
/// with D_q = dN/dX at q (n x 3) (thesis §4.3). Over all points at once this is
/// one matrix product, H^{ab} = E^{ab} Gt with E^{ab} = [w_0 D_0 A_0^{ab} | w_1 D_1
/// A_1^{ab} | ...] and Gt = [D_0 | D_1 | ...]^T; the six blocks a <= b (major
/// symmetry of dP/dF gives H^{ba} = (H^{ab})^T) are stacked into one (6n x 3Q) by
/// (3Q x n) product (hessian_product.hpp). The per-pair 3x3 updates this replaces
/// ran at ~6 % of the FMA peak (Tet20).
template <int N>
double element_hessian(const Material& mat, const BasisTabulation& tab, const Eigen::VectorXd& w, ElementWorkspace<N>& ws,
                       bool project_psd_at_points) {
  const int n = ws.nodes(), Q = tab.num_points, ld = (6 * n + 7) / 8 * 8;
  if (ws.E.cols() < 3 * Q || ws.E.rows() != ld) {
    ws.E.setZero(ld, 3 * Q);  // padding rows stay zero
    ws.Gt.resize(3 * Q, n);
    ws.Hs.resize(ld, n);
  }
  ws.g.setZero();
  double e = 0.0;
  // Node coordinates as rows (n x 3): J and F become dot products of contiguous columns.
  ws.Xt = ws.X.transpose();
  ws.xt = ws.x.transpose();
  ws.gt.setZero();
  const auto& Xt = ws.Xt;
  const auto& xt = ws.xt;
  for (int q = 0; q < Q; ++q) {
    const double wq = reference_gradients_from<N>(tab, w, q, Xt, ws.dNdX);
    const Mat3 F = xt.transpose().lazyProduct(ws.dNdX);
    Mat3 P;
    Mat9 A;
    e += wq * mat.evaluate(F, &P, &A);  // psi, P and dP/dF from one evaluation
    if (project_psd_at_points) A = project_psd(A);
    // Internal forces as rows (n x 3: gt.row(i) = (w P grad N_i)^T), by columns of dN/dX: vectorised over nodes.
    ws.gt.noalias() += ws.dNdX.lazyProduct((wq * P).transpose());
    // Fixed-size views where n is a compile-time constant (Eigen inlines the
    // small products instead of calling its general GEMM).
    using Stride = Eigen::OuterStride<>;
    Eigen::Map<Eigen::Matrix<double, 3, N>, 0, Stride>(ws.Gt.data() + 3 * q, 3, n, Stride(ws.Gt.rows())) =
        ws.dNdX.transpose();
    for (int s = 0; s < 6; ++s) {
      const int a = kHessianPairs[s][0], b = kHessianPairs[s][1];
      Eigen::Matrix3d Aab;  // (c, d) -> w_q dP_ac/dF_bd
      for (int c = 0; c < 3; ++c)
        for (int d = 0; d < 3; ++d) Aab(c, d) = wq * A(a + 3 * c, b + 3 * d);
      Eigen::Map<Eigen::Matrix<double, N, 3>, 0, Stride>(ws.E.data() + s * n + static_cast<std::ptrdiff_t>(3 * q) * ld, n,
                                                         3, Stride(ld))
          .noalias() = ws.dNdX.lazyProduct(Aab);
    }
  }
  for (int i = 0; i < n; ++i) ws.g.template segment<3>(3 * i) = ws.gt.row(i).transpose();
  hessian_product(ws.E.data(), ld, 3 * Q, ws.Gt.data(), static_cast<int>(ws.Gt.rows()), n, ws.Hs.data());
  return e;
}

}  // namespace hofem
