#pragma once
// Elastodynamics of a hyperelastic body (thesis §2.3), put together from three
// parts: the semi-discrete body with its mass model (dynamics/elastic_body.hpp),
// the time stepper that advances its state (dynamics/time_stepper.hpp) and the
// diagnostics of that state (dynamics/dynamics_diagnostics.hpp).
#include "dynamics/dynamics_diagnostics.hpp"
#include "dynamics/elastic_body.hpp"
#include "dynamics/time_stepper.hpp"
#include "parallel/rank_stats.hpp"

#include <Eigen/Core>

#include <functional>
#include <memory>
#include <vector>

namespace hofem {

class DynamicElasticity {
 public:
  DynamicElasticity(const Mesh& mesh, const Material& material, std::vector<PrescribedMotion> motions,
                    DynamicsOptions options);
  // The mesh and the material are kept by reference: temporaries would dangle.
  DynamicElasticity(Mesh&&, const Material&, std::vector<PrescribedMotion>, DynamicsOptions) = delete;
  DynamicElasticity(const Mesh&, Material&&, std::vector<PrescribedMotion>, DynamicsOptions) = delete;

  /// Initial velocity v(X) of the free nodes (prescribed ones follow their motion).
  void set_velocity(const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& v);
  /// Initial velocities, 3 per node (prescribed nodes are reset to their motion).
  void set_velocities(const Eigen::VectorXd& v) { stepper_.set_velocities(v); }
  /// Initial positions, 3 per node (prescribed nodes are reset to their motion).
  void set_positions(const Eigen::VectorXd& x) { stepper_.set_positions(x); }

  /// Continues from a stored state (TimeStepper::restart).
  void restart(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& v) { stepper_.restart(t, x, v); }
  /// Advances by dt. On failure (ok = false) the state is left at the last good step.
  StepReport step() { return stepper_.step(); }
  /// The implicit integrators' linear solver (null before their first step).
  const LinearSolver* linear_solver() const { return stepper_.linear_solver(); }

  double time() const { return stepper_.time(); }
  const Eigen::VectorXd& positions() const { return stepper_.positions(); }
  const Eigen::VectorXd& velocities() const { return stepper_.velocities(); }
  Eigen::VectorXd displacement() const { return positions() - body_->reference(); }
  Energies energies() { return hofem::energies(*body_, positions(), velocities()); }
  Eigen::Vector3d linear_momentum() const { return hofem::linear_momentum(*body_, velocities()); }
  Eigen::Vector3d angular_momentum() const { return hofem::angular_momentum(*body_, positions(), velocities()); }
  double estimate_stable_dt(int iterations = 40) { return hofem::estimate_stable_dt(*body_, positions(), iterations); }

  const DynamicsStats& stats() const { return body_->stats(); }
  const DofMap& dofs() const { return body_->dofs(); }
  const Assembler& assembler() const { return body_->disc().assembler(); }
  /// The mesh the body lives on: the given one, or (distributed) this rank's piece.
  const Mesh& mesh() const { return body_->mesh(); }
  /// Distributed runs: the piece, its halo and the global numbering; else null.
  const DistributedMesh* distributed_mesh() const { return body_->disc().piece(); }
  /// Distributed, after the first step: this rank's figures (parallel/rank_stats.hpp).
  /// Throws std::logic_error otherwise.
  RankStats rank_stats() const;

 private:
  std::unique_ptr<ElasticBody> body_;  ///< not movable: the stepper refers to it
  TimeStepper stepper_;
};

}  // namespace hofem
