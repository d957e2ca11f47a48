// Newton never walks uphill (solver/newton.cpp): on an indefinite Hessian an
// indefinite-capable solver returns an ascent direction, which the descent test
// must replace (projected Hessian, shift, gradient) before the line search.
#include "linalg/linear_solver.hpp"
#include "solver/newton.hpp"
#include "solver/solver_factory.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace hofem {
namespace {

// E(x, y) = (x^2 - 1)^2 + y^2: a double well in x. At x = 0.2 the Hessian's xx
// entry 12 x^2 - 4 = -3.52 is negative, g_x = 4 x (x^2 - 1) = -0.768, so the
// Newton step -g_x / E_xx = -0.218 points uphill (slope +0.167). The projected
// Hessian clamps E_xx at 0 (positive semi-definite, singular).
class DoubleWell final : public NonlinearProblem {
 public:
  int size() const override { return 2; }
  double energy(const Eigen::VectorXd& u) override { return std::pow(u[0] * u[0] - 1.0, 2) + u[1] * u[1]; }
  double gradient(const Eigen::VectorXd& u, Eigen::VectorXd& g) override {
    g.resize(2);
    g << 4.0 * u[0] * (u[0] * u[0] - 1.0), 2.0 * u[1];
    return energy(u);
  }
  void hessian(const Eigen::VectorXd& u, Eigen::VectorXd& g, SparseMatrix& K, bool project) override {
    gradient(u, g);
    const double exx = 12.0 * u[0] * u[0] - 4.0;
    K.resize(2, 2);
    K.setZero();
    K.insert(0, 0) = project ? std::max(exx, 0.0) : exx;
    K.insert(1, 1) = 2.0;
    K.makeCompressed();
  }
  double force_scale(const Eigen::VectorXd&) const override { return 1.0; }
};

// For every accepted step the energy may not rise beyond the rounding band
// (64 eps |E|, the band the line search itself accepts), and the start at
// (0.2, 0) must have needed a fallback direction. With the Armijo constant 0.49
// (below 1/2, so full Newton steps pass near the quadratic minimum) the ascent
// step of the first iteration, E rising 0.0777 < 0.49 x 0.167, would pass the
// Armijo test if it were taken: the check that stops it is the descent test.
// Without that check UMFPACK, CR, MINRES and GMRES all take the ascent step and
// the energy rises at iteration 1 (measured by disabling it).
TEST(NewtonDescent, NeverAcceptsAnEnergyIncrease) {
  for (const char* name : {"eigen-ldlt", "umfpack", "cr+none", "minres+none", "gmres+none"}) {
    DoubleWell problem;
    Eigen::VectorXd u(2);
    u << 0.2, 0.0;
    auto solver = make_linear_solver(name);
    NewtonOptions options;
    options.armijo = 0.49;
    const NewtonResult r = newton_minimize(problem, u, *solver, options);
    EXPECT_TRUE(r.converged) << name << ": " << r.message;
    EXPECT_NEAR(std::fabs(u[0]), 1.0, 1e-8) << name;  // a minimum, |g| <= 1e-9 there
    ASSERT_FALSE(r.history.empty());
    EXPECT_NE(r.history.front().direction, "newton") << name << ": the ascent direction was taken";
    double previous = r.history.front().energy;
    for (size_t k = 1; k < r.history.size(); ++k) {
      const double band = 64.0 * std::numeric_limits<double>::epsilon() * std::fabs(previous);
      EXPECT_LE(r.history[k].energy, previous + band) << name << ": iteration " << k;
      previous = r.history[k].energy;
    }
    EXPECT_LE(problem.energy(u), previous + 64.0 * std::numeric_limits<double>::epsilon() * std::fabs(previous));
  }
}

}  // namespace
}  // namespace hofem
