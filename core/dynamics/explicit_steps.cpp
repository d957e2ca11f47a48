// Forces, accelerations and the explicit integrators of DynamicElasticity.
#include "dynamics/dynamic_elasticity.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace hofem {

namespace {
double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

Eigen::VectorXd DynamicElasticity::internal_forces(const Eigen::VectorXd& x) {
  const auto t0 = std::chrono::steady_clock::now();
  Eigen::VectorXd g;
  disc_->assembler().gradient(material_, x, g);
  ++stats_.gradient_evaluations;
  stats_.assembly_seconds += since(t0);
  return -g;
}

// K(x) w without a Hessian: a central difference of the internal forces along w,
// step eps |x| / |w| (relative truncation ~eps^2, rounding ~1e-16 / eps).
Eigen::VectorXd DynamicElasticity::stiffness_times(const Eigen::VectorXd& x, const Eigen::VectorXd& w) {
  const double wn = w.cwiseAbs().maxCoeff();
  if (wn == 0.0) return Eigen::VectorXd::Zero(x.size());
  const double eps = 1e-6 * (x.cwiseAbs().maxCoeff() + 1e-300) / wn;
  return (internal_forces(x - eps * w) - internal_forces(x + eps * w)) / (2.0 * eps);
}

// f = f_int(x) + rho g + floor - (alpha M + beta K) v, all DOFs.
Eigen::VectorXd DynamicElasticity::forces(const Eigen::VectorXd& x, const Eigen::VectorXd& v) {
  Eigen::VectorXd f = internal_forces(x) + f_gravity_;
  if (options_.floor) {
    ++stats_.floor_evaluations;
    options_.floor->add_forces(x, f);
  }
  if (options_.rayleigh_alpha > 0.0) f -= options_.rayleigh_alpha * mass_->times(v);
  if (options_.rayleigh_beta > 0.0) f -= options_.rayleigh_beta * stiffness_times(x, v);
  return f;
}

// a_f = M_ff^-1 (f_f - M_fp a_p); prescribed entries get the motion's acceleration.
Eigen::VectorXd DynamicElasticity::accelerations(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& v) {
  Eigen::VectorXd f = forces(x, v);
  Eigen::VectorXd a_p = Eigen::VectorXd::Zero(x.size());
  for (const PrescribedMotion& m : motions_)
    if (m.acceleration)
      for (int n : m.nodes) a_p.segment<3>(3 * n) = m.acceleration(mesh_.nodes.col(n), t);
  Eigen::VectorXd a = a_p;
  if (mass_->lumped()) {
    for (int i : dofs_.free_dofs()) a[i] = f[i] / mass_->diagonal()[i];
  } else {
    if (moving_boundary_) f -= mass_->consistent_times(a_p);
    const auto t0 = std::chrono::steady_clock::now();
    Eigen::VectorXd af;
    mass_->solve_free(dofs_.restrict(f), af);
    stats_.solve_seconds += since(t0);
    dofs_.add_free(af, a);
  }
  return a;
}

void DynamicElasticity::step_explicit_euler() {
  const double h = options_.dt;
  const Eigen::VectorXd a = accelerations(t_, x_, v_);
  x_ += h * v_;
  v_ += h * a;
  impose_motion(t_ + h, x_, &v_);
}

void DynamicElasticity::step_symplectic_euler() {
  const double h = options_.dt;
  v_ += h * accelerations(t_, x_, v_);
  impose_motion(t_ + h, x_, &v_);  // the boundary's velocity over the step is its own
  x_ += h * v_;
  impose_motion(t_ + h, x_, &v_);
}

// Velocity Verlet: kick, drift, kick. With velocity-dependent (damping) forces
// the second kick uses the half-step velocity, which makes damped runs first
// order; undamped runs are second order and symplectic.
void DynamicElasticity::step_leapfrog() {
  const double h = options_.dt;
  if (!a_valid_) a_ = accelerations(t_, x_, v_);
  v_ += 0.5 * h * a_;
  x_ += h * v_;
  impose_motion(t_ + h, x_, nullptr);
  a_ = accelerations(t_ + h, x_, v_);
  v_ += 0.5 * h * a_;
  impose_motion(t_ + h, x_, &v_);
  a_valid_ = true;
}

void DynamicElasticity::step_rk4() {
  const double h = options_.dt;
  const Eigen::VectorXd k1x = v_, k1v = accelerations(t_, x_, v_);
  Eigen::VectorXd x2 = x_ + 0.5 * h * k1x, v2 = v_ + 0.5 * h * k1v;
  impose_motion(t_ + 0.5 * h, x2, &v2);
  const Eigen::VectorXd k2v = accelerations(t_ + 0.5 * h, x2, v2);
  Eigen::VectorXd x3 = x_ + 0.5 * h * v2, v3 = v_ + 0.5 * h * k2v;
  impose_motion(t_ + 0.5 * h, x3, &v3);
  const Eigen::VectorXd k3v = accelerations(t_ + 0.5 * h, x3, v3);
  Eigen::VectorXd x4 = x_ + h * v3, v4 = v_ + h * k3v;
  impose_motion(t_ + h, x4, &v4);
  const Eigen::VectorXd k4v = accelerations(t_ + h, x4, v4);
  x_ += h / 6.0 * (k1x + 2.0 * v2 + 2.0 * v3 + v4);
  v_ += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
  impose_motion(t_ + h, x_, &v_);
}

}  // namespace hofem
