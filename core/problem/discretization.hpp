#pragma once
// The discretised body a problem works on, serial or distributed alike: the
// mesh (the given one, or this rank's piece of it), its element rules, the DOF
// map with its constraints, the assembler, the global numbering of the free
// DOFs and the reductions over ranks. The static and dynamic problems hold one
// and call it without asking whether the run is distributed: serially the
// reductions are identities and the numbering is the DOF map's.
//
// Built for one mesh at one order; a multilevel method (the p-multigrid) sees
// it through its MeshView and builds its hierarchy of orders from that.
#include "assembly/assembler.hpp"
#include "assembly/distributed_dofs.hpp"
#include "assembly/dof_map.hpp"
#include "distributed/distributed_mesh.hpp"
#include "embedded/element_rules.hpp"
#include "mesh/mesh.hpp"
#include "parallel/collectives.hpp"
#include "parallel/rank_stats.hpp"
#include "linalg/linear_solver.hpp"
#include "solver/solver_choice.hpp"

#include <Eigen/Core>

#include <memory>
#include <string>
#include <vector>

namespace hofem {

class Discretization {
 public:
  /// On `mesh` (kept by reference). Distributed (collective): starts hypre,
  /// partitions the elements over MPI_COMM_WORLD (recursive coordinate
  /// bisection) and keeps this rank's piece. `rules` are given on `mesh`;
  /// the nodes they leave without support are decided there too (a node this
  /// rank's elements leave unsupported may be supported by another rank's).
  Discretization(const Mesh& mesh, bool distributed, const ElementRules& rules, int quadrature_degree);
  /// Distributed on a piece each rank made itself (box_piece via
  /// distribute_piece: no rank holds the whole mesh); no element rules.
  Discretization(std::unique_ptr<DistributedMesh> piece, int quadrature_degree);
  Discretization(Mesh&&, bool, const ElementRules&, int) = delete;  // kept by reference
  Discretization(const Discretization&) = delete;  // the assembler refers to the DOF map
  Discretization& operator=(const Discretization&) = delete;

  /// The DOF map with all DOFs of `nodes` (ids on mesh()) and of the
  /// unsupported nodes constrained, and a new assembler over it (its sparsity
  /// pattern). Called before use, and again when the constraints change (a
  /// released node set); a solver made before must then be made again.
  void constrain(const std::vector<int>& nodes);

  const Mesh& mesh() const { return piece_ ? piece_->mesh() : *given_; }
  const DofMap& dofs() const { return dofs_; }
  const Assembler& assembler() const { return *assembler_; }
  /// The element rules on mesh() (restricted to the piece).
  const ElementRules& rules() const { return rules_; }

  bool distributed() const { return piece_ != nullptr; }
  /// Distributed: the piece, its halo and the global numbering (after
  /// make_solver); else null.
  const DistributedMesh* piece() const { return piece_.get(); }
  const DistributedDofs* rows() const { return rows_.get(); }
  MPI_Comm comm() const { return piece_ ? piece_->comm : MPI_COMM_WORLD; }
  long long global_elements() const { return piece_ ? piece_->local.global_elements : mesh().num_elements(); }
  long long global_free_dofs() const { return rows_ ? rows_->global_rows : dofs_.num_free(); }

  /// Node ids of the mesh given to the constructor as ids on mesh() (those on
  /// this piece; all of them serially, or for a piece made by its rank).
  std::vector<int> local_nodes(const std::vector<int>& ids) const;
  /// A nodal field of the given mesh (3 values per node) on mesh().
  Eigen::VectorXd local_nodal(const Eigen::VectorXd& given) const;

  // Reductions over the ranks (identities serially).
  double sum(double value) const { return piece_ ? sum_over_ranks(value, comm()) : value; }
  int sum(int value) const { return piece_ ? sum_over_ranks(value, comm()) : value; }
  void sum(Eigen::Ref<Eigen::VectorXd> values) const {
    if (piece_) sum_over_ranks(values, comm());
  }
  double min(double value) const { return piece_ ? min_over_ranks(value, comm()) : value; }
  double max(double value) const { return piece_ ? max_over_ranks(value, comm()) : value; }
  bool any(bool flag) const { return piece_ ? any_rank(flag, comm()) : flag; }
  /// Partial nodal sums (each rank's elements, 3 per node of mesh()) made whole, on owners and ghosts.
  void complete_nodal(Eigen::VectorXd& partial) const {
    if (piece_) piece_->nodes.sum(partial);
  }
  /// The same over the free DOFs (needs make_solver's numbering).
  void complete_free(Eigen::VectorXd& partial) const {
    if (rows_) rows_->free.sum(partial);
  }
  /// Dot products of consistent vectors, each node (DOF) counted once over all ranks.
  double dot_nodal(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const {
    return piece_ ? piece_->nodes.dot(a, b) : a.dot(b);
  }
  double dot_free(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const {
    return rows_ ? rows_->free.dot(a, b) : a.dot(b);
  }
  /// The nodes whose nodal terms (floor contact) this rank counts: null for all.
  const std::vector<char>* counted_nodes() const { return piece_ ? &owned_ : nullptr; }
  /// f(); distributed, every rank learns whether it threw E on any and all
  /// throw E(what) together (parallel/collectives.hpp).
  template <class E, class F>
  void on_all_ranks_or_throw(const char* what, F&& f) const {
    hofem::on_all_ranks_or_throw<E>(distributed(), comm(), what, std::forward<F>(f));
  }

  /// `spec` resolved for this system ("auto": solver_choice.hpp); distributed
  /// runs always solve on hypre with spec.distributed.
  SolverChoice choose_solver(const SolverSpec& spec) const;
  /// The name a report gives the solver of `choice`: its spec's, or "hypre".
  std::string solver_name(const SolverChoice& choice) const { return piece_ ? "hypre" : choice.spec.name(); }
  /// The solver of choose_solver(spec).spec: serial, make_linear_solver with
  /// this mesh view (`blocks` for block preconditioners); distributed
  /// (collective), hypre on the global numbering of the free DOFs, built here.
  std::unique_ptr<LinearSolver> make_solver(const SolverSpec& resolved, const std::vector<int>* blocks);
  /// Distributed: this rank's figures with `solver`'s; else std::logic_error.
  RankStats rank_stats(const LinearSolver& solver) const;

 private:
  const Mesh* given_ = nullptr;  ///< the mesh given to the constructor; null for a piece made by its rank
  std::unique_ptr<DistributedMesh> piece_;
  ElementRules rules_;
  std::vector<int> unsupported_;
  std::vector<char> owned_;  ///< distributed: per node of the piece, 1 if this rank owns it
  int quadrature_degree_ = -1;
  DofMap dofs_;
  std::unique_ptr<Assembler> assembler_;
  std::unique_ptr<DistributedDofs> rows_;
};

}  // namespace hofem
