#pragma once
// Advances an ElasticBody's state (positions, velocities, time) by one of the
// integrators of dynamics/integrator.hpp: the explicit ones from the body's
// accelerations (explicit_steps.cpp), backward Euler as the minimisation of the
// incremental potential and the semi-implicit step with the linear solver
// (implicit_steps.cpp, symbolic analysis reused every step). A failed step
// leaves the state at the last good one and says why.
#include "dynamics/elastic_body.hpp"
#include "linalg/linear_solver.hpp"

#include <Eigen/Core>

#include <memory>
#include <string>

namespace hofem {

struct StepReport {
  double time = 0.0;  ///< at the end of the step
  bool ok = true;
  std::string message;  ///< why not ok (instability, inversion, Newton failure)
  int newton_iterations = 0;
  int linear_iterations = 0;
  int setups = 0;        ///< the linear solver's factorisations / preconditioner set-ups
  int setup_reuses = 0;  ///< matrices an iterative solver took on an earlier set-up
  double newton_residual = 0.0;
  /// Newton iterations whose direction came from the PSD-projected Hessian
  /// (the Hessian as assembled refused, or solver.hessian = projected).
  int projected_directions = 0;
  double seconds = 0.0;
};

class TimeStepper {
 public:
  /// Starts at rest in the reference configuration, the prescribed nodes at their motion at t = 0.
  explicit TimeStepper(ElasticBody& body);
  ~TimeStepper();
  TimeStepper(const TimeStepper&) = delete;  // refers to its body
  TimeStepper& operator=(const TimeStepper&) = delete;

  /// Positions and velocities, 3 per node (prescribed nodes are reset to their motion).
  void set_positions(const Eigen::VectorXd& x) { set_state(x, x_, "positions"); }
  void set_velocities(const Eigen::VectorXd& v) { set_state(v, v_, "velocities"); }
  /// Continues from a stored state: time t, positions and velocities (3 per
  /// node; prescribed nodes are reset to their motion at t). The linear solver
  /// and its set-ups are kept.
  void restart(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& v);
  /// Advances by the body's dt. On failure (ok = false) the state is left at the last good step.
  StepReport step();

  double time() const { return t_; }
  const Eigen::VectorXd& positions() const { return x_; }
  const Eigen::VectorXd& velocities() const { return v_; }
  /// The implicit integrators' linear solver (null before their first step).
  const LinearSolver* linear_solver() const { return solver_.get(); }

 private:
  class IncrementalPotential;
  void set_state(const Eigen::VectorXd& value, Eigen::VectorXd& into, const char* what);
  void step_explicit_euler();
  void step_symplectic_euler();
  void step_leapfrog();
  void step_rk4();
  void step_semi_implicit(StepReport& report);
  void step_implicit_euler(StepReport& report, double h);
  void implicit_euler_adaptive(StepReport& report, double h, int depth);
  void ensure_linear_solver();
  /// The scale of energies a stable explicit run can reach (once per state set).
  double energy_reference();
  /// Why a step failed when the explicit integrator became unstable, with the stable dt.
  std::string instability_hint();

  ElasticBody& body_;
  const DynamicsOptions& options_;       ///< body_'s
  std::unique_ptr<LinearSolver> solver_;  ///< implicit integrators
  SparseMatrix K_;
  Eigen::VectorXd x_, v_;  ///< all DOFs
  Eigen::VectorXd a_;      ///< leapfrog's acceleration at the current state
  bool a_valid_ = false;
  double t_ = 0.0;
  double energy_reference_ = -1.0;
};

}  // namespace hofem
