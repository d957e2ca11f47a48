#include "dynamics/time_stepper.hpp"

#include "dynamics/dynamics_diagnostics.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace hofem {

TimeStepper::TimeStepper(ElasticBody& body)
    : body_(body), options_(body.options()), x_(body.reference()), v_(Eigen::VectorXd::Zero(x_.size())) {
  body_.impose_motion(0.0, x_, &v_);
}

TimeStepper::~TimeStepper() = default;

// A new state: the prescribed nodes back on their motion; leapfrog's
// acceleration and the explicit runs' energy scale recomputed on the next step.
void TimeStepper::set_state(const Eigen::VectorXd& value, Eigen::VectorXd& into, const char* what) {
  if (value.size() != into.size() || !value.allFinite())
    throw std::invalid_argument(fmt::format("dynamics: {} need {} finite entries", what, into.size()));
  into = value;
  body_.impose_motion(t_, x_, &v_);
  a_valid_ = false;
  energy_reference_ = -1.0;
}

void TimeStepper::restart(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& v) {
  if (!std::isfinite(t)) throw std::invalid_argument("dynamics: restart time must be finite");
  t_ = t;  // first: set_state imposes the motion at t_
  set_positions(x);
  set_velocities(v);
}

void TimeStepper::ensure_linear_solver() {
  if (solver_) return;
  Discretization& disc = body_.disc();
  const SolverChoice choice = disc.choose_solver(options_.solver);
  body_.counters().linear_solver = disc.solver_name(choice);
  body_.counters().linear_solver_reason = choice.reason;
  body_.counters().hessian_nonzeros = disc.assembler().pattern().nonzeros();
  solver_ = disc.make_solver(choice.spec, options_.preconditioner_blocks ? &*options_.preconditioner_blocks : nullptr);
  // The semi-implicit step's own matrix; backward Euler's Newton keeps its own.
  if (options_.integrator == Integrator::SemiImplicit) K_ = disc.assembler().new_matrix();
}

// Scale of energies a stable run can reach: the initial kinetic and elastic
// energy, the work gravity can do over the body's extent (and its height above
// a floor), and the kinetic energy of the boundary's motion.
double TimeStepper::energy_reference() {
  if (energy_reference_ >= 0.0) return energy_reference_;
  const Mesh& mesh = body_.mesh();
  const Eigen::Vector3d lo = mesh.nodes.rowwise().minCoeff(), hi = mesh.nodes.rowwise().maxCoeff();
  double extent = (hi - lo).norm() + (x_ - body_.reference()).cwiseAbs().maxCoeff();
  if (options_.floor) extent += std::abs(options_.floor->depth(lo));
  const double gravity_work = body_.gravity_load().cwiseAbs().sum() * extent;
  const double elastic = body_.elastic_energy(x_);
  Eigen::VectorXd vb = Eigen::VectorXd::Zero(x_.size());
  for (int i : body_.dofs().constrained_dofs()) vb[i] = v_[i];
  const double boundary = 0.5 * vb.dot(body_.mass().times(vb));
  energy_reference_ = std::max({kinetic_energy(body_, v_) + elastic, gravity_work, boundary,
                                std::numeric_limits<double>::min()});
  return energy_reference_;
}

// Backward Euler with step halving: a step whose Newton solve fails (a
// nonconvex region such as a buckling tube, where the projected Newton
// converges slowly) is redone as two half steps, up to kMaxHalvings deep. The
// state only changes when a (sub)step converges.
void TimeStepper::implicit_euler_adaptive(StepReport& report, double h, int depth) {
  constexpr int kMaxHalvings = 4;
  const double t0 = t_;
  StepReport attempt;
  step_implicit_euler(attempt, h);
  report.newton_iterations += attempt.newton_iterations;
  report.linear_iterations += attempt.linear_iterations;
  report.setups += attempt.setups;
  report.setup_reuses += attempt.setup_reuses;
  report.projected_directions += attempt.projected_directions;
  report.newton_residual = attempt.newton_residual;
  if (attempt.ok) return;
  if (depth >= kMaxHalvings) {
    report.ok = false;
    report.message = attempt.message + fmt::format(" (after {} halvings of dt)", kMaxHalvings);
    return;
  }
  ++body_.counters().step_halvings;
  implicit_euler_adaptive(report, 0.5 * h, depth + 1);
  if (!report.ok) return;
  t_ = t0 + 0.5 * h;
  implicit_euler_adaptive(report, 0.5 * h, depth + 1);
  t_ = t0;  // step() advances the time by the whole step
}

std::string TimeStepper::instability_hint() {
  // Explicit Euler has no stable dt for an undamped mode (stability_limit 0):
  // naming a bound "dt < 0" would be true and useless, so the hint says what helps.
  if (stability_limit(options_.integrator) == 0.0)
    return fmt::format(": unstable; {} at dt = {:.3e} amplifies every undamped mode at any dt (its stability "
                       "region holds no imaginary eigenvalue): a stable dt needs damping (\"damping\": "
                       "{{\"alpha\", \"beta\"}}) or another integrator",
                       integrator_name(options_.integrator), options_.dt);
  double stable = std::numeric_limits<double>::quiet_NaN();
  try {
    stable = estimate_stable_dt(body_, x_);
  } catch (const MaterialDomainError&) {
    // The last good state is too close to inversion for the difference
    // quotients; the message then says so through the NaN.
  }
  const std::string bound = std::isnan(stable) ? std::string("a smaller dt (the last state is too close to "
                                                             "inversion to estimate omega_max)")
                                               : fmt::format("dt < {:.3e} here", stable);
  return fmt::format(": unstable; {} at dt = {:.3e} needs {} (omega_max from power iteration on M^-1 K)",
                     integrator_name(options_.integrator), options_.dt, bound);
}

StepReport TimeStepper::step() {
  const auto t0 = std::chrono::steady_clock::now();
  if (body_.release_due_motions(t_)) {
    // A new pattern and DOF map: mesh-aware preconditioners start over (and global rows).
    if (solver_) {
      solver_.reset();
      ensure_linear_solver();
    }
    a_valid_ = false;
  }
  StepReport report;
  const Eigen::VectorXd x_old = x_, v_old = v_;
  const double t_old = t_;
  const bool explicit_scheme = is_explicit(options_.integrator);
  if (explicit_scheme) energy_reference();
  try {
    switch (options_.integrator) {
      case Integrator::ExplicitEuler: step_explicit_euler(); break;
      case Integrator::SymplecticEuler: step_symplectic_euler(); break;
      case Integrator::Leapfrog: step_leapfrog(); break;
      case Integrator::RK4: step_rk4(); break;
      case Integrator::SemiImplicit: step_semi_implicit(report); break;
      case Integrator::ImplicitEuler: implicit_euler_adaptive(report, options_.dt, 0); break;
    }
  } catch (const MaterialDomainError& e) {
    report.ok = false;
    report.message = fmt::format("t = {:.6g}: {} (an element inverted{})", t_old + options_.dt, e.what(),
                                 explicit_scheme ? "; the explicit step may be unstable at this dt" : "");
  }
  const Discretization& disc = body_.disc();
  if (report.ok) {
    t_ = t_old + options_.dt;
    const bool finite = !disc.any(!(x_.allFinite() && v_.allFinite()));  // every rank rolls back together
    if (!finite) {
      report.ok = false;
      report.message = fmt::format("t = {:.6g}: non-finite positions or velocities", t_);
    } else if (explicit_scheme) {
      const double kinetic = kinetic_energy(body_, v_);
      if (kinetic > options_.instability_factor * energy_reference_) {
        report.ok = false;
        report.message = fmt::format("t = {:.6g}: kinetic energy {:.3e} > {:.0e} x the run's energy scale {:.3e}",
                                     t_, kinetic, options_.instability_factor, energy_reference_);
      }
    }
  }
  if (!report.ok) {
    x_ = x_old;
    v_ = v_old;
    t_ = t_old;
    a_valid_ = false;
    if (explicit_scheme) report.message += instability_hint();
  }
  if (options_.floor && report.ok) {
    DynamicsStats& stats = body_.counters();
    stats.contact_node_steps += disc.sum(options_.floor->contacts(x_, disc.counted_nodes()));
    stats.max_penetration = std::max(stats.max_penetration, disc.max(options_.floor->max_depth(x_)));
  }
  report.time = t_;
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return report;
}

}  // namespace hofem
