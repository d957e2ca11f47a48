#pragma once
// The coefficients of Chebyshev smoothing on an interval [lower, upper] of the
// preconditioned operator's spectrum (Saad, Iterative Methods for Sparse Linear
// Systems, 2nd ed., Alg. 12.1): with S the smoother's inverse (a diagonal or
// block diagonal) and r_k the current residual,
//   d_0 = S r_0 / theta,   d_k = c_old d_{k-1} + c_res S r_k,   x += d_k,
// so that after k steps the error is p_k(S A) e_0 with
//   p_k(lambda) = T_k((theta - lambda) / delta) / T_k(theta / delta),
// theta and delta the interval's centre and half-width: the polynomial of
// degree k smallest on [lower, upper] among those with p(0) = 1. The smoothers
// that apply it (solver/p_multigrid.cpp) take the coefficients from here; the
// unit test checks p_k against the closed form of T_k.
#include <stdexcept>

namespace hofem {

class ChebyshevRecurrence {
 public:
  ChebyshevRecurrence(double lower, double upper)
      : theta_(0.5 * (upper + lower)), delta_(0.5 * (upper - lower)), sigma_(theta_ / delta_), rho_(1.0 / sigma_) {
    if (!(lower > 0.0) || !(upper > lower))
      throw std::invalid_argument("ChebyshevRecurrence: needs 0 < lower < upper");
  }

  /// The first step divides S r_0 by this (the interval's centre).
  double theta() const { return theta_; }

  struct Step {
    double c_old;  ///< factor of the previous direction
    double c_res;  ///< factor of S r_k
  };
  /// The next step's coefficients (rho_{k+1} = 1 / (2 sigma - rho_k)).
  Step next() {
    const double rho_next = 1.0 / (2.0 * sigma_ - rho_);
    const Step s{rho_next * rho_, 2.0 * rho_next / delta_};
    rho_ = rho_next;
    return s;
  }

 private:
  double theta_, delta_, sigma_, rho_;
};

}  // namespace hofem
