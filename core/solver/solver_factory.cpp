#include "solver/solver_factory.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <stdexcept>
#include <string>

#include "linalg/algebraic_preconditioners.hpp"
#include "linalg/cholmod_solver.hpp"
#include "linalg/eigen_ldlt_solver.hpp"
#include "linalg/hypre_pcg.hpp"
#include "linalg/krylov.hpp"
#include "linalg/umfpack_solver.hpp"
#include "solver/additive_schwarz.hpp"
#include "linalg/boomeramg.hpp"
#include "solver/p_multigrid.hpp"
#include "solver/solver_registry.hpp"

namespace hofem {

namespace {

// The "amg..." preconditioners where the mesh is known: BoomerAMG
// (linalg/boomeramg.hpp) told which DOF each matrix row is - so that it can
// check the node-interleaved layout hypre's systems AMG assumes - and, for
// variants with interpolation vectors, the rigid rotations of the free nodes.
class BoomerAmgOnMesh final : public BoomerAmgPreconditioner {
 public:
  explicit BoomerAmgOnMesh(const std::string& variant) : BoomerAmgPreconditioner(variant, boomeramg_options(variant)) {}
  void set_mesh_view(const MeshView& d) override {
    if (!d.valid()) return;
    set_row_layout(d.dofs->free_dofs(), amg().options().interp_vec_variant > 0 ? rigid_rotations(d) : Eigen::MatrixXd());
  }
};

// A registered BoomerAMG variant told its DOF layout by the mesh view: the
// "amg..." preconditioners and hypre's PCG's.
std::unique_ptr<BoomerAmgPreconditioner> make_boomeramg(const std::string& variant) {
  return std::make_unique<BoomerAmgOnMesh>(variant);
}

std::unique_ptr<Preconditioner> make_of_kind(PreconditionerKind kind, std::string_view name) {
  switch (kind) {
    case PreconditionerKind::Identity:
      return make_identity_preconditioner();
    case PreconditionerKind::Jacobi:
      return make_jacobi_preconditioner();
    case PreconditionerKind::BlockJacobi:
      return make_block_jacobi_preconditioner();
    case PreconditionerKind::Ic0:
      return make_ic0_preconditioner();
    case PreconditionerKind::EigenIct:
      return make_eigen_ict_preconditioner();
    case PreconditionerKind::BoomerAmg:
      return make_boomeramg(std::string(name));
    case PreconditionerKind::PMultigrid:
      return std::make_unique<PMultigridPreconditioner>();
    case PreconditionerKind::Schwarz:
      return std::make_unique<AdditiveSchwarzPreconditioner>();
  }
  throw std::logic_error("make_preconditioner: unknown PreconditionerKind");
}

}  // namespace

std::unique_ptr<Preconditioner> make_preconditioner(std::string_view name) {
  const PreconditionerEntry* entry = find_preconditioner(name);
  if (!entry)
    throw std::invalid_argument(
        fmt::format("unknown preconditioner '{}' (valid: {})", name, fmt::join(preconditioner_names(), ", ")));
  std::unique_ptr<Preconditioner> made = make_of_kind(entry->kind, entry->name);
  made->set_name(std::string(entry->name));  // the registry's name, the one home of it
  return made;
}

namespace {

std::unique_ptr<LinearSolver> make_unbudgeted(const SolverSpec& spec) {
  if (!spec.method) throw std::logic_error("make_linear_solver: resolve \"auto\" first (resolve_linear_solver)");
  switch (*spec.method) {
    case SolverMethod::Cholmod:
      return std::make_unique<CholmodSolver>();
    case SolverMethod::EigenLdlt:
      return std::make_unique<EigenLdltSolver>();
    case SolverMethod::Umfpack:
      return std::make_unique<UmfpackSolver>();
    case SolverMethod::HyprePcg:
      return std::make_unique<HyprePcgSolver>(make_boomeramg(spec.preconditioner));  // "amg" (SolverSpec::parse)
    case SolverMethod::Cg:
    case SolverMethod::Cr:
    case SolverMethod::Minres:
    case SolverMethod::Gmres:
      return std::make_unique<KrylovSolver>(*spec.method, make_preconditioner(spec.preconditioner), spec.krylov);
  }
  throw std::logic_error("make_linear_solver: unknown SolverMethod");
}

}  // namespace

std::unique_ptr<LinearSolver> make_linear_solver(const SolverSpec& spec) {
  std::unique_ptr<LinearSolver> solver = make_unbudgeted(spec);
  apply_iteration_budget(*solver, spec.fixed_iterations);
  return solver;
}

std::unique_ptr<LinearSolver> make_linear_solver(std::string_view name) {
  return make_linear_solver(SolverSpec::parse(name));
}

}  // namespace hofem
