#pragma once
// Elastodynamics of a hyperelastic body (thesis §2.3): M a = f_int(x) + f_ext
// + f_floor - D v over the free DOFs, with prescribed motion on node sets,
// gravity, a rigid floor and Rayleigh damping D = alpha M + beta K, advanced by
// one of the integrators of dynamics/integrator.hpp.
//
// Only what the run needs is built, once: the lumped mass for explicit
// integrators (the consistent one, and its Cholesky factor, only when asked
// for), the consistent mass matrix and the linear solver (symbolic analysis
// reused every step) for the implicit ones; no Hessian ever for explicit
// integrators (stiffness-proportional damping uses a directional difference of
// internal forces); no contact work without a floor; the gravity load once.
// DynamicsStats counts what was built and evaluated.
#include "assembly/assembler.hpp"
#include "assembly/distributed_dofs.hpp"
#include "assembly/dof_map.hpp"
#include "dynamics/floor_contact.hpp"
#include "dynamics/integrator.hpp"
#include "dynamics/mass_model.hpp"
#include "dynamics/prescribed_motion.hpp"
#include "material/material.hpp"
#include "mesh/mesh.hpp"
#include "solver/rank_figures.hpp"
#include "solver/discretization.hpp"
#include "solver/distributed_system.hpp"
#include "solver/linear_solver.hpp"
#include "solver/newton.hpp"
#include "solver/problem_options.hpp"
#include "solver/solver_choice.hpp"

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

struct Energies {
  double kinetic = 0.0, elastic = 0.0, gravity = 0.0, floor = 0.0;
  double total() const { return kinetic + elastic + gravity + floor; }
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
  int factorizations = 0;        ///< of the linear solver (numeric)
  int newton_iterations = 0;
  int linear_iterations = 0;
  int floor_evaluations = 0;     ///< 0 without a floor
  int step_halvings = 0;         ///< implicit Euler steps redone as two half steps
  int releases = 0;              ///< times prescribed node sets were released (DOF map rebuilt)
  int contact_node_steps = 0;    ///< nodes in contact, summed over steps
  double max_penetration = 0.0;
  /// Polar decompositions (SVDs) of F computed by the material: one per
  /// quadrature point and evaluation for corotated, none for the others.
  long long polar_decompositions = 0;
  double assembly_seconds = 0.0, solve_seconds = 0.0;
};

struct StepReport {
  double time = 0.0;  ///< at the end of the step
  bool ok = true;
  std::string message;  ///< why not ok (instability, inversion, Newton failure)
  int newton_iterations = 0;
  int linear_iterations = 0;
  double newton_residual = 0.0;
  double seconds = 0.0;
};

class DynamicElasticity {
 public:
  DynamicElasticity(const Mesh& mesh, const Material& material, std::vector<PrescribedMotion> motions,
                    DynamicsOptions options);
  // The mesh and the material are kept by reference: temporaries would dangle.
  DynamicElasticity(Mesh&&, const Material&, std::vector<PrescribedMotion>, DynamicsOptions) = delete;
  DynamicElasticity(const Mesh&, Material&&, std::vector<PrescribedMotion>, DynamicsOptions) = delete;
  ~DynamicElasticity();
  DynamicElasticity(const DynamicElasticity&) = delete;  // members refer to disc_
  DynamicElasticity& operator=(const DynamicElasticity&) = delete;

  /// Initial velocity v(X) of the free nodes (prescribed ones follow their motion).
  void set_velocity(const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& v);
  /// Initial velocities, 3 per node (prescribed nodes are reset to their motion).
  void set_velocities(const Eigen::VectorXd& v);
  /// Initial positions, 3 per node (prescribed nodes are reset to their motion).
  void set_positions(const Eigen::VectorXd& x);

  /// Advances by dt. On failure (ok = false) the state is left at the last good step.
  StepReport step();

  double time() const { return t_; }
  const Eigen::VectorXd& positions() const { return x_; }
  const Eigen::VectorXd& velocities() const { return v_; }
  Eigen::VectorXd displacement() const;
  /// Energies; the elastic one relative to the rest state (materials such as
  /// Stable Neo-Hookean have psi(I) != 0).
  Energies energies();
  /// Linear and angular momentum (about the origin) from the mass in use.
  Eigen::Vector3d linear_momentum() const;
  Eigen::Vector3d angular_momentum() const;
  /// Largest stable dt of the integrator at the current state: stability_limit /
  /// omega_max, omega_max^2 the largest eigenvalue of M^-1 K by power iteration
  /// with Hessian-vector products from differences of internal forces (no
  /// Hessian is assembled). Infinity for the implicit integrators.
  double estimate_stable_dt(int iterations = 40);

  const DynamicsStats& stats() const;
  const DynamicsOptions& options() const { return options_; }
  const DofMap& dofs() const { return dofs_; }
  const Assembler& assembler() const { return disc_->assembler(); }
  /// The mesh the body lives on: the given one, or (distributed) this rank's piece.
  const Mesh& mesh() const { return mesh_; }
  /// Distributed runs: the piece, its halo and the global numbering; else null.
  const DistributedMesh* distributed_mesh() const { return disc_->piece(); }
  const DistributedDofs* distributed_dofs() const { return disc_->rows(); }
  /// Distributed, after the first step: this rank's figures (parallel/rank_stats.hpp).
  /// Throws std::logic_error otherwise.
  RankStats rank_stats() const;

 private:
  class IncrementalPotential;
  // Forces and accelerations (dynamics_forces.cpp).
  Eigen::VectorXd internal_forces(const Eigen::VectorXd& x);
  Eigen::VectorXd forces(const Eigen::VectorXd& x, const Eigen::VectorXd& v);
  Eigen::VectorXd accelerations(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& v);
  /// Elastic energy of the whole body (summed over ranks when distributed).
  double elastic_energy(const Eigen::VectorXd& x) const;
  Eigen::VectorXd stiffness_times(const Eigen::VectorXd& x, const Eigen::VectorXd& w);
  void impose_motion(double t, Eigen::VectorXd& x, Eigen::VectorXd* v) const;
  double kinetic_energy() const;
  // Integrators.
  void step_explicit_euler();
  void step_symplectic_euler();
  void step_leapfrog();
  void step_rk4();
  void step_semi_implicit(StepReport& report);
  void step_implicit_euler(StepReport& report);
  void implicit_euler_adaptive(StepReport& report, double h, int depth);
  void ensure_linear_solver();
  void release_due_motions();

  /// The mesh (or this rank's piece), element rules, DOF map, assembler, global
  /// numbering and reductions over ranks; first, as everything below refers to it.
  std::unique_ptr<Discretization> disc_;
  const Mesh& mesh_;    ///< disc_'s: the given mesh, or the piece
  const DofMap& dofs_;  ///< disc_'s (rebuilt in place when a node set is released)
  const Material& material_;
  std::vector<PrescribedMotion> motions_;
  DynamicsOptions options_;
  std::vector<char> released_;    ///< per motion: released (every rank alike, whether or not it has its nodes)
  std::unique_ptr<MassModel> mass_;
  std::unique_ptr<LinearSolver> solver_;       ///< implicit integrators
  SparseMatrix K_;
  Eigen::VectorXd f_gravity_;     ///< consistent gravity load, all DOFs
  Eigen::VectorXd x_, v_;         ///< all DOFs
  Eigen::VectorXd a_;             ///< leapfrog's acceleration at the current state
  bool a_valid_ = false;
  double t_ = 0.0;
  double energy_reference_ = -1.0;
  double elastic_force_scale_ = 0.0;
  std::optional<double> rest_energy_;  ///< elastic energy of the reference state  ///< (2 mu + lambda) L^2, L the reference extent
  bool moving_boundary_ = false;
  mutable DynamicsStats stats_;
};

}  // namespace hofem
