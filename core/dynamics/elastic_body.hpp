#pragma once
// The semi-discrete equations of motion of a hyperelastic body (thesis §2.3):
// M a = f_int(x) + f_ext + f_floor - D v over the free DOFs, with prescribed
// motion on node sets, gravity, a rigid floor and Rayleigh damping
// D = alpha M + beta K. What an integrator needs to advance them (forces,
// accelerations, K w, the boundary's motion) and nothing of time stepping.
//
// Only what the run needs is built, once: the mass model of the integrator's
// kind (dynamics/mass_model.hpp), the gravity load, no Hessian (stiffness
// products are directional differences of internal forces), no contact work
// without a floor. DynamicsStats counts what was built and evaluated.
#include "dynamics/floor_contact.hpp"
#include "dynamics/integrator.hpp"
#include "dynamics/mass_model.hpp"
#include "dynamics/prescribed_motion.hpp"
#include "material/material.hpp"
#include "mesh/mesh.hpp"
#include "problem/discretization.hpp"
#include "problem/problem_options.hpp"

#include <Eigen/Core>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace hofem {

/// The shared options (ProblemOptions: quadrature, element rules, solver with
/// its Krylov budget, Newton, distribution) and time stepping's own.
/// Distributed runs (ProblemOptions::distributed) support implicit Euler
/// without stiffness damping so far; each rank integrates every element term
/// (elastic, mass, gravity) of its elements and every nodal term (floor) of its
/// owned nodes, and positions, velocities and displacements are those of
/// mesh(), this rank's piece.
struct DynamicsOptions : ProblemOptions {
  Integrator integrator = Integrator::ImplicitEuler;
  double dt = 1.0 / 60.0;
  double density = 1000.0;
  /// Default: lumped for explicit integrators, consistent for the others.
  std::optional<MassKind> mass;
  /// Default: row sums for order 1, HRZ for higher orders (row sums go negative).
  std::optional<MassLumping> lumping;
  double rayleigh_alpha = 0.0;  ///< D = alpha M + beta K (1/s and s)
  double rayleigh_beta = 0.0;
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();
  std::optional<Floor> floor;
  /// Explicit runs stop as unstable when the mechanical energy exceeds this
  /// factor times its reference (initial energy, gravity and boundary work scales).
  double instability_factor = 1e6;
};

/// What was built and how often things were evaluated, over the whole run.
struct DynamicsStats {
  std::string linear_solver;         ///< implicit integrators: the solver used ("auto" resolved)
  std::string linear_solver_reason;  ///< why ("given" when named)
  std::string mass;              ///< "lumped (row-sum)", "lumped (HRZ)" or "consistent"
  int mass_matrices_built = 0;   ///< sparse consistent mass matrices
  int mass_factorizations = 0;   ///< Cholesky of the consistent mass (explicit + consistent only)
  int gradient_evaluations = 0;  ///< internal-force assemblies
  int energy_evaluations = 0;
  int hessian_assemblies = 0;
  int symbolic_analyses = 0;     ///< of the linear solver
  int factorizations = 0;        ///< of the linear solver (numeric; an iterative solver's preconditioner set-ups)
  int setup_reuses = 0;          ///< matrices an iterative solver took on an earlier set-up (KrylovOptions::setup_reuse)
  int newton_iterations = 0;
  int linear_iterations = 0;
  /// Newton directions not taken from the Hessian as assembled (NewtonIteration::direction):
  /// the solver refused it or its direction did not descend (an indefinite
  /// Hessian, CG meeting p^T A p <= 0), so the PSD-projected Hessian, a shifted
  /// one or the gradient gave the direction. Zero when every Hessian was used as is.
  int projected_directions = 0, shifted_directions = 0, gradient_directions = 0;
  long long hessian_nonzeros = 0;  ///< implicit integrators: stored entries of the Hessian's free-DOF pattern (this rank's, both triangles)
  int floor_evaluations = 0;     ///< 0 without a floor
  int step_halvings = 0;         ///< implicit Euler steps redone as two half steps
  int releases = 0;              ///< times prescribed node sets were released (DOF map rebuilt)
  int contact_node_steps = 0;    ///< nodes in contact, summed over steps
  double max_penetration = 0.0;
  /// Polar decompositions (SVDs) of F computed by the material: one per
  /// quadrature point and evaluation for corotated, none for the others.
  long long polar_decompositions = 0;
  double assembly_seconds = 0.0, solve_seconds = 0.0;
  double setup_seconds = 0.0;  ///< of solve_seconds: factorisations / preconditioner set-ups (LinearSolver::setup_seconds)
};

class ElasticBody {
 public:
  /// Validates the options (throws std::invalid_argument naming the bad one)
  /// and the prescribed node sets (out of range, or in two sets).
  ElasticBody(const Mesh& mesh, const Material& material, std::vector<PrescribedMotion> motions,
              DynamicsOptions options);
  ElasticBody(Mesh&&, const Material&, std::vector<PrescribedMotion>, DynamicsOptions) = delete;  // kept by reference
  ElasticBody(const Mesh&, Material&&, std::vector<PrescribedMotion>, DynamicsOptions) = delete;
  ElasticBody(const ElasticBody&) = delete;  // members refer to disc_
  ElasticBody& operator=(const ElasticBody&) = delete;

  /// The mesh (or this rank's piece), element rules, DOF map, assembler, global
  /// numbering and reductions over ranks.
  Discretization& disc() { return *disc_; }
  const Discretization& disc() const { return *disc_; }
  const Mesh& mesh() const { return disc_->mesh(); }
  const DofMap& dofs() const { return disc_->dofs(); }
  const Material& material() const { return material_; }
  const DynamicsOptions& options() const { return options_; }
  const MassModel& mass() const { return *mass_; }
  /// The consistent gravity load over all DOFs (distributed: this rank's share).
  const Eigen::VectorXd& gravity_load() const { return f_gravity_; }
  /// (2 mu + lambda) L^2, L the reference extent: the elastic force of a unit strain.
  double elastic_force_scale() const { return elastic_force_scale_; }
  /// Some node set still prescribed moves (its acceleration enters the forces).
  bool moving_boundary() const { return moving_boundary_; }
  /// The reference positions, 3 per node.
  Eigen::Map<const Eigen::VectorXd> reference() const;

  /// x (and v) of the prescribed nodes set to their motion at time t.
  void impose_motion(double t, Eigen::VectorXd& x, Eigen::VectorXd* v) const;
  /// The prescribed nodes' accelerations at time t, zero elsewhere.
  Eigen::VectorXd prescribed_accelerations(double t) const;
  /// f_int(x) = -dPsi/dx over all DOFs (a share when distributed).
  Eigen::VectorXd internal_forces(const Eigen::VectorXd& x);
  /// K(x) w by a central difference of the internal forces (no Hessian).
  Eigen::VectorXd stiffness_times(const Eigen::VectorXd& x, const Eigen::VectorXd& w);
  /// f = f_int(x) + rho g + floor - (alpha M + beta K) v, all DOFs.
  Eigen::VectorXd forces(const Eigen::VectorXd& x, const Eigen::VectorXd& v);
  /// a_f = M_ff^-1 (f_f - M_fp a_p); prescribed entries get the motion's acceleration.
  Eigen::VectorXd accelerations(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& v);
  /// Elastic energy of the whole body (summed over ranks when distributed).
  double elastic_energy(const Eigen::VectorXd& x);
  /// Elastic energy of the reference state, computed once (materials such as
  /// Stable Neo-Hookean have psi(I) != 0).
  double rest_energy();

  /// Releases every node set whose release time t has reached (collectively:
  /// every rank releases the same sets at the same step). Returns true when the
  /// DOF map, its pattern and the mass were rebuilt.
  bool release_due_motions(double t);

  /// The counters, for the integrators to add to.
  DynamicsStats& counters() { return stats_; }
  /// The counters with the mass model's and the material's figures filled in.
  const DynamicsStats& stats() const;

 private:
  std::unique_ptr<Discretization> disc_;  ///< first: everything below refers to it
  const Material& material_;
  std::vector<PrescribedMotion> motions_;
  DynamicsOptions options_;
  std::vector<char> released_;  ///< per motion: released (every rank alike, whether or not it has its nodes)
  std::unique_ptr<MassModel> mass_;
  Eigen::VectorXd f_gravity_;
  double elastic_force_scale_ = 0.0;
  std::optional<double> rest_energy_;
  bool moving_boundary_ = false;
  mutable DynamicsStats stats_;
};

}  // namespace hofem
