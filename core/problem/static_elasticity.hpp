#pragma once
// Static equilibrium of a hyperelastic body: minimise the total potential
//   Pi(u) = sum_e int psi(F) dX - int f . u dX
// over displacements u with Dirichlet values on node sets (eliminated), by the
// damped Newton of solver/newton.hpp. On failure the load (body force and
// prescribed displacement together) is applied in smaller steps.
#include "assembly/assembler.hpp"
#include "assembly/distributed_dofs.hpp"
#include "assembly/dof_map.hpp"
#include "material/material.hpp"
#include "mesh/mesh.hpp"
#include "problem/rank_figures.hpp"
#include "problem/discretization.hpp"
#include "solver/distributed_system.hpp"
#include "linalg/linear_solver.hpp"
#include "solver/newton.hpp"
#include "problem/problem_options.hpp"
#include "solver/solver_choice.hpp"

#include <Eigen/Core>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace hofem {

using VectorField = std::function<Eigen::Vector3d(const Eigen::Vector3d&)>;

struct DirichletCondition {
  std::vector<int> nodes;     ///< all three components of these nodes are prescribed
  VectorField displacement;   ///< u_D(X); empty means fixed (zero)
};

/// The shared options (ProblemOptions: quadrature, element rules, solver,
/// Newton, distribution) and the static solve's own.
struct StaticOptions : ProblemOptions {
  int load_degree = -1;        ///< body-force integration; < 0: default_quadrature_degrees(...).load, 2p + 2
  /// Extra external load at full load factor, all 3 * num_nodes DOFs (e.g. surface
  /// tractions integrated by the caller); empty = none. Distributed: given on the global mesh.
  Eigen::VectorXd external_load;
  int max_load_halvings = 6;   ///< a failed load step is halved at most this many times in a row
  /// Tangent predictor at each load step: u += -K^-1 (dg/dload) dload, with K at
  /// the last converged state. Without it the prescribed boundary displacement
  /// arrives as a jump that folds the boundary layer of elements; with it the
  /// first step at full load starts from the linearised (for the first step: the
  /// linear-elastic) solution.
  bool predictor = true;
};

struct StaticReport {
  bool converged = false;
  int newton_iterations = 0;  ///< summed over load steps
  int linear_iterations = 0;  ///< iterative solvers: summed over Newton iterations, load steps and predictors
  int load_steps = 0;
  std::vector<NewtonResult> steps;
  double assembly_seconds = 0.0;  ///< energy / gradient / Hessian assembly
  double solve_seconds = 0.0;     ///< factorisations and triangular solves
  double setup_seconds = 0.0;     ///< pattern, tabulation, load vector
  int factorizations = 0;
  int symbolic_analyses = 0;
  /// SVDs of F computed by the material: one per quadrature point of every
  /// element and Hessian assembly for corotated, none for the others.
  long long polar_decompositions = 0;
  std::string linear_solver;         ///< the solver used ("auto" resolved; "hypre" when distributed)
  std::string linear_solver_reason;  ///< why ("given" when named by the caller)
  std::string message;
};

/// The last load step's residual_over_tolerance (solver/newton.hpp): <= 1 exactly
/// when the solve converged (a failed solve ends on its failed step); +inf when
/// no step ran.
double residual_over_tolerance(const StaticReport& report, double rtol);

class StaticElasticity final : public NonlinearProblem {
 public:
  StaticElasticity(const Mesh& mesh, const Material& material, std::vector<DirichletCondition> dirichlet,
                   VectorField body_force, StaticOptions options = {});

  /// Distributed on a piece each rank made itself (e.g. box_piece via
  /// distribute_piece: no rank holds the whole mesh). Dirichlet node ids are the
  /// piece's; options.distributed is implied; element rules and external loads
  /// are not taken (they are given on a whole mesh). Collective.
  StaticElasticity(std::unique_ptr<DistributedMesh> piece, const Material& material,
                   std::vector<DirichletCondition> dirichlet, VectorField body_force, StaticOptions options = {});
  // The mesh and the material are kept by reference: temporaries would dangle.
  StaticElasticity(Mesh&&, const Material&, std::vector<DirichletCondition>, VectorField, StaticOptions = {}) = delete;
  StaticElasticity(const Mesh&, Material&&, std::vector<DirichletCondition>, VectorField, StaticOptions = {}) = delete;
  StaticElasticity(std::unique_ptr<DistributedMesh>, Material&&, std::vector<DirichletCondition>, VectorField,
                   StaticOptions = {}) = delete;

  StaticReport solve();

  /// Displacement of every node of mesh(), 3 per node (valid after solve()).
  const Eigen::VectorXd& displacement() const { return u_full_; }
  /// The mesh the problem lives on: the given one, or (distributed) this rank's piece.
  const Mesh& mesh() const { return disc_->mesh(); }
  /// Distributed runs: the piece and its halo; else null.
  const DistributedMesh* distributed_mesh() const { return disc_->piece(); }
  /// Distributed: this rank's figures (mesh piece, halo, matrix, AMG and Krylov
  /// timings) so far; collective-free. Serial: throws std::logic_error.
  RankStats rank_stats() const;
  /// Free DOFs over all ranks.
  long long global_free_dofs() const { return disc_->global_free_dofs(); }
  const Assembler& assembler() const { return disc_->assembler(); }
  const DofMap& dofs() const { return disc_->dofs(); }

  // NonlinearProblem over the free DOFs (load factor applied).
  int size() const override { return disc_->dofs().num_free(); }
  double energy(const Eigen::VectorXd& u) override;
  double gradient(const Eigen::VectorXd& u, Eigen::VectorXd& g) override;
  void hessian(const Eigen::VectorXd& u, Eigen::VectorXd& g, SparseMatrix& K, bool project) override;
  double force_scale(const Eigen::VectorXd& g0) const override;
  double dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const override { return disc_->dot_free(a, b); }

 private:
  void set_state(const Eigen::VectorXd& u_free);  // fills x_ and u_full_
  double external_work() const;                   // f_ext . u over the whole body
  // The DOF map (with `constrained`, ids on mesh()), assembler, solver and load on
  // mesh() (the piece when distributed).
  void finish_setup(const std::vector<int>& constrained, const Eigen::VectorXd& external, const VectorField& body_force);
  /// The tangent predictor from load `from` to `to` at state u (converged at `from`).
  Eigen::VectorXd predict(const Eigen::VectorXd& u, double from, double to);
  /// The step of a constant-tangent (quadratic) problem from u to the equilibrium at load `to`.
  Eigen::VectorXd linear_step(const Eigen::VectorXd& u, double to);
  /// The mesh (or this rank's piece), DOF map, assembler, global numbering and
  /// reductions; before solver_, which refers to its DOF map and numbering.
  std::unique_ptr<Discretization> disc_;
  const Material& material_;
  std::vector<DirichletCondition> dirichlet_;
  StaticOptions options_;
  SolverChoice solver_choice_;  ///< options_.solver resolved
  std::unique_ptr<LinearSolver> solver_;
  Eigen::VectorXd f_ext_;     ///< consistent body-force vector at full load (all DOFs)
  Eigen::VectorXd u_dirichlet_;  ///< prescribed displacement at full load (all DOFs, zero elsewhere)
  Eigen::VectorXd u_full_, x_, g_full_;
  /// The matrix of linear_step(), kept: a P3 Hessian's arrays are ~1e8 bytes, and
  /// allocating them again costs as much as assembling the values.
  SparseMatrix K_;
  double load_ = 1.0;
  double step_force_ = 0.0;  ///< |dg/dload| * dload of the current load step (force scale)
  double assembly_seconds_ = 0.0;
  double setup_seconds_hint_ = 0.0;
  int predictor_iterations_ = 0;
};

}  // namespace hofem
