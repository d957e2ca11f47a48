// Chebyshev smoothing's coefficients against the closed form of its error
// polynomial (Saad, Iterative Methods for Sparse Linear Systems, 2nd ed., §12.1).
#include "linalg/chebyshev_recurrence.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace hofem {
namespace {

// T_k(x) from its trigonometric / hyperbolic form, independent of any recurrence.
double chebyshev_t(int k, double x) {
  if (std::fabs(x) <= 1.0) return std::cos(k * std::acos(x));
  const double t = std::cosh(k * std::acosh(std::fabs(x)));
  return (x < 0.0 && k % 2 == 1) ? -t : t;
}

// The smoother applied to a 1x1 system lambda x = lambda (S = 1, x* = 1, x_0 = 0)
// leaves the error 1 - x_k = p_k(lambda) = T_k((theta - lambda)/delta) / T_k(theta/delta).
// Checked at degrees 1-6, for eigenvalues inside the interval (|p| <= 1/T_k(sigma))
// and outside it (0 < lambda < lower, where p grows towards 1). Both sides in
// double: measured worst 2.0e-13 relative to max(|p|, 1e-3) (the closed form's
// acos / acosh lose digits near the interval's ends); 1e-10 leaves 500x, while
// a wrong first step or coefficient changes p by O(1) of itself (the first step
// alone by (theta - delta) / theta = 10 % for range 20).
TEST(ChebyshevRecurrence, ErrorIsTheScaledChebyshevPolynomial) {
  for (const double range : {4.0, 20.0, 100.0}) {
    const double upper = 2.4, lower = upper / range;
    const double theta = 0.5 * (upper + lower), delta = 0.5 * (upper - lower);
    for (int degree = 1; degree <= 6; ++degree) {
      for (int i = 0; i <= 40; ++i) {
        const double lambda = 0.5 * lower + (upper - 0.5 * lower) * i / 40.0;
        ChebyshevRecurrence cheb(lower, upper);
        double x = 0.0, r = lambda;  // r = b - A x
        double d = r / cheb.theta();
        x += d;
        for (int k = 1; k < degree; ++k) {
          const ChebyshevRecurrence::Step c = cheb.next();
          r -= lambda * d;
          d = c.c_old * d + c.c_res * r;
          x += d;
        }
        const double expected = chebyshev_t(degree, (theta - lambda) / delta) / chebyshev_t(degree, theta / delta);
        EXPECT_LE(std::fabs((1.0 - x) - expected), 1e-10 * std::max(std::fabs(expected), 1e-3))
            << "range " << range << " degree " << degree << " lambda " << lambda;
      }
    }
  }
}

TEST(ChebyshevRecurrence, RefusesAnEmptyOrNonPositiveInterval) {
  EXPECT_THROW(ChebyshevRecurrence(0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(ChebyshevRecurrence(1.0, 1.0), std::invalid_argument);
  EXPECT_THROW(ChebyshevRecurrence(std::nan(""), 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace hofem
