#include "basis/simplex_orthonormal_basis.hpp"


#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace hofem {

namespace {

// Homogenised Jacobi recurrence: R_n = P_n^(alpha,0)(X / T) T^n for polynomials
// X (= x t) and T (= t) given with their gradients; fills R[0..n] and dR.
// From a1 P_{n+1} = (a2 + a3 x) P_n - a4 P_{n-1}, multiplied by t^{n+1}:
//   a1 R_{n+1} = (a2 T + a3 X) R_n - a4 T^2 R_{n-1}.
template <int D>
void homogenised_jacobi(int n, int alpha, double X, const double* dX, double T, const double* dT,
                        std::vector<double>& R, std::vector<std::array<double, 3>>& dR) {
  R.assign(n + 1, 0.0);
  dR.assign(n + 1, {0.0, 0.0, 0.0});
  R[0] = 1.0;
  if (n == 0) return;
  const double a = alpha;
  R[1] = ((a + 2.0) * X + a * T) / 2.0;
  for (int c = 0; c < D; ++c) dR[1][c] = ((a + 2.0) * dX[c] + a * dT[c]) / 2.0;
  for (int k = 1; k < n; ++k) {
    const double s = 2.0 * k + a;
    const double a1 = 2.0 * (k + 1) * (k + a + 1) * s;
    const double a2 = (s + 1) * a * a;
    const double a3 = s * (s + 1) * (s + 2);
    const double a4 = 2.0 * (k + a) * k * (s + 2);
    const double lin = a2 * T + a3 * X;
    R[k + 1] = (lin * R[k] - a4 * T * T * R[k - 1]) / a1;
    for (int c = 0; c < D; ++c) {
      const double dlin = a2 * dT[c] + a3 * dX[c];
      dR[k + 1][c] = (dlin * R[k] + lin * dR[k][c] - a4 * (2.0 * T * dT[c] * R[k - 1] + T * T * dR[k - 1][c])) / a1;
    }
  }
}

}  // namespace

std::vector<std::array<int, 3>> total_degree_exponents(int dim, int p) {
  std::vector<std::array<int, 3>> e;
  for (int a = 0; a <= p; ++a)
    for (int b = 0; b <= (dim > 1 ? p - a : 0); ++b)
      for (int c = 0; c <= (dim > 2 ? p - a - b : 0); ++c) e.push_back({a, b, c});
  return e;
}

OrthonormalSimplexBasis::OrthonormalSimplexBasis(CellType cell, int order) : cell_(cell), order_(order) {
  if (order < 0) throw std::invalid_argument(fmt::format("basis order must be >= 0, got {}", order));
  if (cell != CellType::Segment && cell != CellType::Triangle && cell != CellType::Tetrahedron)
    throw std::invalid_argument(fmt::format("OrthonormalSimplexBasis: {} is not a simplex", name(cell)));
  dim_ = dimension(cell);
  // Norms in closed form, from int_{-1}^{1} (1-x)^a P_n^(a,0)(x)^2 dx = 2^(a+1)/(2n+a+1)
  // and the collapsed-coordinate Jacobians (Karniadakis & Sherwin §3.2.2):
  //   segment:  ||psi_i||^2   = 2/(2i+1)
  //   triangle: ||psi_ij||^2  = 2/(2i+1) * 2/(2i+2j+2)                       on the biunit
  //   tet:      ||psi_ijk||^2 = 2/(2i+1) * 2/(2i+2j+2) * 2/(2i+2j+2k+3)      triangle/tet,
  // and the unit simplex has 1/4 (triangle) or 1/8 (tet) of the biunit measure.
  index_ = total_degree_exponents(dim_, order);
  for (const auto& [i, j, k] : index_) {
    const double nij = 2.0 / (2 * i + 1) * 2.0 / (2 * i + 2 * j + 2);
    if (dim_ == 1) scale_.push_back(std::sqrt((2.0 * i + 1.0) / 2.0));
    else if (dim_ == 2) scale_.push_back(1.0 / std::sqrt(nij / 4.0));
    else scale_.push_back(1.0 / std::sqrt(nij * 2.0 / (2 * i + 2 * j + 2 * k + 3) / 8.0));
  }
}

void OrthonormalSimplexBasis::evaluate(const double* x, double* values, double* gradients) const {
  evaluate_unscaled(x, values, gradients);
  for (int m = 0; m < size(); ++m) {
    values[m] *= scale_[m];
    if (gradients)
      for (int c = 0; c < dim_; ++c) gradients[m * dim_ + c] *= scale_[m];
  }
}

// psi in the order of index_ (i outermost, then j, then k). Every one-dimensional
// factor is a whole recurrence sequence computed once per (i) or (i, j), so a
// point costs O(p^d) work, not O(p^(d+1)).
void OrthonormalSimplexBasis::evaluate_unscaled(const double* x, double* values, double* gradients) const {
  const int p = order_;
  std::vector<double> Q, R, P;
  std::vector<std::array<double, 3>> dQ, dR, dP;
  if (dim_ == 1) {  // Legendre on [-1, 1]
    const double one[3] = {1.0, 0.0, 0.0}, zero[3] = {0.0, 0.0, 0.0};
    homogenised_jacobi<1>(p, 0, x[0], one, 1.0, zero, P, dP);
    for (int m = 0; m <= p; ++m) {
      values[m] = P[m];
      if (gradients) gradients[m] = dP[m][0];
    }
    return;
  }
  // Biunit coordinates r, s, u = 2x - 1 (so d/dx = 2 d/dr).
  const double r = 2.0 * x[0] - 1.0, s = 2.0 * x[1] - 1.0;
  const double zero[3] = {0.0, 0.0, 0.0};
  int m = 0;
  if (dim_ == 2) {
    // Q_i = P_i(a) ((1-s)/2)^i with a t = r + (1+s)/2, t = (1-s)/2 (Legendre: alpha = 0).
    const double X = r + (1.0 + s) / 2.0, dX[3] = {1.0, 0.5, 0.0};
    const double T = (1.0 - s) / 2.0, dT[3] = {0.0, -0.5, 0.0};
    homogenised_jacobi<2>(p, 0, X, dX, T, dT, Q, dQ);
    const double ds[3] = {0.0, 1.0, 0.0};
    for (int i = 0; i <= p; ++i) {
      homogenised_jacobi<2>(p - i, 2 * i + 1, s, ds, 1.0, zero, P, dP);  // P_j^(2i+1,0)(s)
      for (int j = 0; i + j <= p; ++j, ++m) {
        values[m] = Q[i] * P[j];
        if (gradients)
          for (int c = 0; c < 2; ++c) gradients[2 * m + c] = 2.0 * (dQ[i][c] * P[j] + Q[i] * dP[j][c]);
      }
    }
    return;
  }
  const double u = 2.0 * x[2] - 1.0;
  // Q_i = P_i(a) t1^i with a t1 = 1 + r + (s+u)/2, t1 = -(s+u)/2.
  const double X1 = 1.0 + r + (s + u) / 2.0, dX1[3] = {1.0, 0.5, 0.5};
  const double T1 = -(s + u) / 2.0, dT1[3] = {0.0, -0.5, -0.5};
  homogenised_jacobi<3>(p, 0, X1, dX1, T1, dT1, Q, dQ);
  // R_j^(2i+1) = P_j^(2i+1,0)(b) t2^j with b t2 = s + (1+u)/2, t2 = (1-u)/2.
  const double X2 = s + (1.0 + u) / 2.0, dX2[3] = {0.0, 1.0, 0.5};
  const double T2 = (1.0 - u) / 2.0, dT2[3] = {0.0, 0.0, -0.5};
  const double du[3] = {0.0, 0.0, 1.0};
  for (int i = 0; i <= p; ++i) {
    homogenised_jacobi<3>(p - i, 2 * i + 1, X2, dX2, T2, dT2, R, dR);
    for (int j = 0; i + j <= p; ++j) {
      homogenised_jacobi<3>(p - i - j, 2 * i + 2 * j + 2, u, du, 1.0, zero, P, dP);  // P_k^(2i+2j+2,0)(u)
      const double qr = Q[i] * R[j];
      for (int k = 0; i + j + k <= p; ++k, ++m) {
        values[m] = qr * P[k];
        if (gradients)
          for (int c = 0; c < 3; ++c)
            gradients[3 * m + c] = 2.0 * ((dQ[i][c] * R[j] + Q[i] * dR[j][c]) * P[k] + qr * dP[k][c]);
      }
    }
  }
}

}  // namespace hofem
