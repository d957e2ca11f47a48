#include "problem/discretization.hpp"

#include "assembly/mesh_view.hpp"

#include "parallel/mpi_runtime.hpp"
#include "solver/distributed_system.hpp"
#include "problem/rank_figures.hpp"
#include "solver/solver_factory.hpp"

#include <stdexcept>

namespace hofem {

Discretization::Discretization(const Mesh& mesh, bool distributed, const ElementRules& rules, int quadrature_degree)
    : given_(&mesh), rules_(rules), unsupported_(unsupported_nodes(mesh, rules)), quadrature_degree_(quadrature_degree) {
  if (!distributed) return;
  ensure_hypre();
  piece_ = std::make_unique<DistributedMesh>(distribute_mesh(MPI_COMM_WORLD, mesh));
  rules_.stiffness = restrict_to_elements(piece_->local, rules_.stiffness);
  rules_.mass = restrict_to_elements(piece_->local, rules_.mass);
  unsupported_ = to_local_nodes(piece_->local, unsupported_);
  owned_.resize(piece_->mesh().num_nodes());
  for (int n = 0; n < piece_->mesh().num_nodes(); ++n) owned_[n] = piece_->local.owns(n);
}

Discretization::Discretization(std::unique_ptr<DistributedMesh> piece, int quadrature_degree)
    : piece_(std::move(piece)), quadrature_degree_(quadrature_degree) {
  ensure_hypre();
  owned_.resize(piece_->mesh().num_nodes());
  for (int n = 0; n < piece_->mesh().num_nodes(); ++n) owned_[n] = piece_->local.owns(n);
}

void Discretization::constrain(const std::vector<int>& nodes) {
  std::vector<int> all = nodes;
  all.insert(all.end(), unsupported_.begin(), unsupported_.end());
  dofs_ = DofMap(mesh().num_nodes(), all);
  assembler_ = std::make_unique<Assembler>(mesh(), dofs_, quadrature_degree_);
  assembler_->set_element_rules(rules_);
}

std::vector<int> Discretization::local_nodes(const std::vector<int>& ids) const {
  return piece_ && given_ ? to_local_nodes(piece_->local, ids) : ids;
}

Eigen::VectorXd Discretization::local_nodal(const Eigen::VectorXd& given) const {
  if (!piece_ || !given_ || given.size() == 0) return given;
  const LocalMesh& local = piece_->local;
  Eigen::VectorXd mine(3 * local.mesh.num_nodes());
  for (int i = 0; i < local.mesh.num_nodes(); ++i) mine.segment<3>(3 * i) = given.segment<3>(3 * local.global_node[i]);
  return mine;
}

SolverChoice Discretization::choose_solver(const SolverSpec& spec) const {
  if (piece_) return {spec, "distributed"};
  return resolve_linear_solver(spec, {dofs_.num_free(), mesh().order, !rules_.empty()});
}

std::unique_ptr<LinearSolver> Discretization::make_solver(const SolverSpec& resolved, const std::vector<int>* blocks) {
  if (!piece_) {
    std::unique_ptr<LinearSolver> solver = make_linear_solver(resolved);
    solver->set_mesh_view({&mesh(), &dofs_, blocks});
    return solver;
  }
  // The global rows of this DOF map; the hypre system refers to them, so a
  // solver made before must be gone (constrain() says so).
  rows_ = std::make_unique<DistributedDofs>(distribute_dofs(*piece_, dofs_));
  auto hypre = std::make_unique<DistributedHypreSolver>(*rows_, resolved.distributed);
  hypre->system().set_coordinates(mesh(), dofs_);
  apply_iteration_budget(*hypre, resolved.fixed_iterations);
  return hypre;
}

RankStats Discretization::rank_stats(const LinearSolver& solver) const {
  if (!piece_ || !rows_) throw std::logic_error("Discretization::rank_stats: not a distributed run with a solver");
  return hofem::rank_stats(*piece_, *rows_, *assembler_, solver);
}

}  // namespace hofem
