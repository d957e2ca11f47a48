#pragma once
// Gauss–Jacobi quadrature on [-1, 1] with weight (1 - x)^alpha (1 + x)^beta
// (Gauss–Legendre is alpha = beta = 0), thesis §3.3.1 / Algorithm 7.
//
// Method: Golub–Welsch eigenvalues of the Jacobi matrix give starting values
// (accurate to ~1e-15 absolute), then Newton on P_n^(alpha,beta) polishes every
// node in the working type `Real`. The weights use the closed form
//   w_i = R * 2^(alpha+beta+1) / ((1 - x_i^2) P_n'(x_i)^2),
//   R   = Gamma(n+alpha+1) Gamma(n+beta+1) / (Gamma(n+alpha+beta+1) n!)
// (Abramowitz & Stegun 25.4.33), which is far more accurate than the squared
// eigenvector components of Golub–Welsch. Instantiated with long double (64-bit
// mantissa) and rounded, nodes and weights are correct to about 1 ulp in double;
// the test suite checks that against a __float128 instantiation.
#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <stdexcept>
#include <vector>

namespace hofem::detail {

template <class Real>
struct JacobiEval {
  Real value;
  Real derivative;
};

/// P_n^(alpha,beta)(x) by the three-term recurrence (Karniadakis & Sherwin, App. A).
template <class Real>
Real jacobi_polynomial(int n, int alpha, int beta, Real x) {
  if (n == 0) return Real(1);
  const Real a = Real(alpha), b = Real(beta);
  Real p_prev = Real(1);
  Real p = ((a + b + Real(2)) * x + (a - b)) / Real(2);
  for (int k = 1; k < n; ++k) {
    const Real kk = Real(k);
    const Real s = Real(2) * kk + a + b;
    const Real a1 = Real(2) * (kk + Real(1)) * (kk + a + b + Real(1)) * s;
    const Real a2 = (s + Real(1)) * (a * a - b * b);
    const Real a3 = s * (s + Real(1)) * (s + Real(2));
    const Real a4 = Real(2) * (kk + a) * (kk + b) * (s + Real(2));
    const Real p_next = ((a2 + a3 * x) * p - a4 * p_prev) / a1;
    p_prev = p;
    p = p_next;
  }
  return p;
}

/// Value and derivative; d/dx P_n^(a,b) = (n+a+b+1)/2 P_{n-1}^(a+1,b+1), valid everywhere.
template <class Real>
JacobiEval<Real> jacobi_with_derivative(int n, int alpha, int beta, Real x) {
  JacobiEval<Real> e{jacobi_polynomial<Real>(n, alpha, beta, x), Real(0)};
  if (n > 0)
    e.derivative = Real(n + alpha + beta + 1) / Real(2) *
                   jacobi_polynomial<Real>(n - 1, alpha + 1, beta + 1, x);
  return e;
}

/// Starting values: eigenvalues of the symmetric Jacobi matrix (Golub & Welsch 1969).
inline Eigen::VectorXd golub_welsch_nodes(int n, int alpha, int beta) {
  const double a = alpha, b = beta;
  Eigen::VectorXd diag(n), sub(std::max(n - 1, 0));
  for (int k = 0; k < n; ++k) {
    const double s = 2.0 * k + a + b;
    diag[k] = (k == 0) ? (b - a) / (a + b + 2.0) : (b * b - a * a) / (s * (s + 2.0));
  }
  for (int k = 1; k < n; ++k) {
    const double s = 2.0 * k + a + b;
    sub[k - 1] = std::sqrt(4.0 * k * (k + a) * (k + b) * (k + a + b) /
                           (s * s * (s + 1.0) * (s - 1.0)));
  }
  if (n == 1) return diag;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es;
  es.computeFromTridiagonal(diag, sub, Eigen::EigenvaluesOnly);
  return es.eigenvalues();  // ascending
}

/// Nodes (ascending) and weights of the n-point Gauss–Jacobi rule, computed in Real.
template <class Real>
void gauss_jacobi(int n, int alpha, int beta, std::vector<Real>& x, std::vector<Real>& w) {
  if (n < 1) throw std::invalid_argument("gauss_jacobi: need at least one point");
  if (alpha < 0 || beta < 0) throw std::invalid_argument("gauss_jacobi: alpha, beta must be >= 0");
  const Eigen::VectorXd guess = golub_welsch_nodes(n, alpha, beta);
  x.assign(n, Real(0));
  w.assign(n, Real(0));
  // Quadratic convergence from a ~1e-15 start reaches any working precision used
  // here (<= 113 bits) within 3 steps; a fixed 6 steps leave the node oscillating
  // within the rounding of Real, which is all the precision there is.
  for (int i = 0; i < n; ++i) {
    Real xi = Real(guess[i]);
    for (int it = 0; it < 6; ++it) {
      const JacobiEval<Real> e = jacobi_with_derivative<Real>(n, alpha, beta, xi);
      xi -= e.value / e.derivative;
    }
    x[i] = xi;
  }
  if (alpha == beta) {  // symmetric weight: make the rule exactly symmetric
    for (int i = 0; i < n / 2; ++i) {
      const Real m = (x[n - 1 - i] - x[i]) / Real(2);
      x[i] = -m;
      x[n - 1 - i] = m;
    }
    if (n % 2 == 1) x[n / 2] = Real(0);
  }
  Real ratio = Real(1);  // R for integer alpha, beta
  for (int k = 1; k <= alpha; ++k) ratio *= Real(n + k) / Real(n + beta + k);
  Real two_pow = Real(1);
  for (int k = 0; k < alpha + beta + 1; ++k) two_pow *= Real(2);
  for (int i = 0; i < n; ++i) {
    const Real d = jacobi_with_derivative<Real>(n, alpha, beta, x[i]).derivative;
    w[i] = ratio * two_pow / ((Real(1) - x[i] * x[i]) * d * d);
  }
  if (alpha == beta)
    for (int i = 0; i < n / 2; ++i) w[n - 1 - i] = w[i] = (w[i] + w[n - 1 - i]) / Real(2);
}

}  // namespace hofem::detail
