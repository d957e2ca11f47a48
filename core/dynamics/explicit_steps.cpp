// The explicit integrators of TimeStepper, from the body's accelerations.
#include "dynamics/time_stepper.hpp"

namespace hofem {

void TimeStepper::step_explicit_euler() {
  const double h = options_.dt;
  const Eigen::VectorXd a = body_.accelerations(t_, x_, v_);
  x_ += h * v_;
  v_ += h * a;
  body_.impose_motion(t_ + h, x_, &v_);
}

void TimeStepper::step_symplectic_euler() {
  const double h = options_.dt;
  v_ += h * body_.accelerations(t_, x_, v_);
  body_.impose_motion(t_ + h, x_, &v_);  // the boundary's velocity over the step is its own
  x_ += h * v_;
  body_.impose_motion(t_ + h, x_, &v_);
}

// Velocity Verlet: kick, drift, kick. With velocity-dependent (damping) forces
// the second kick uses the half-step velocity, which makes damped runs first
// order; undamped runs are second order and symplectic.
void TimeStepper::step_leapfrog() {
  const double h = options_.dt;
  if (!a_valid_) a_ = body_.accelerations(t_, x_, v_);
  v_ += 0.5 * h * a_;
  x_ += h * v_;
  body_.impose_motion(t_ + h, x_, nullptr);
  a_ = body_.accelerations(t_ + h, x_, v_);
  v_ += 0.5 * h * a_;
  body_.impose_motion(t_ + h, x_, &v_);
  a_valid_ = true;
}

void TimeStepper::step_rk4() {
  const double h = options_.dt;
  const Eigen::VectorXd k1x = v_, k1v = body_.accelerations(t_, x_, v_);
  Eigen::VectorXd x2 = x_ + 0.5 * h * k1x, v2 = v_ + 0.5 * h * k1v;
  body_.impose_motion(t_ + 0.5 * h, x2, &v2);
  const Eigen::VectorXd k2v = body_.accelerations(t_ + 0.5 * h, x2, v2);
  Eigen::VectorXd x3 = x_ + 0.5 * h * v2, v3 = v_ + 0.5 * h * k2v;
  body_.impose_motion(t_ + 0.5 * h, x3, &v3);
  const Eigen::VectorXd k3v = body_.accelerations(t_ + 0.5 * h, x3, v3);
  Eigen::VectorXd x4 = x_ + h * v3, v4 = v_ + h * k3v;
  body_.impose_motion(t_ + h, x4, &v4);
  const Eigen::VectorXd k4v = body_.accelerations(t_ + h, x4, v4);
  x_ += h / 6.0 * (k1x + 2.0 * v2 + 2.0 * v3 + v4);
  v_ += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
  body_.impose_motion(t_ + h, x_, &v_);
}

}  // namespace hofem
