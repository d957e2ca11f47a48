#pragma once
// Linear solvers and preconditioners made from their registered names
// (solver/solver_registry.hpp): the one place that knows every concrete class.
#include "assembly/mesh_view.hpp"  // what the made solvers and preconditioners are handed (set_mesh_view)
#include "linalg/linear_solver.hpp"
#include "linalg/preconditioner.hpp"
#include "solver/solver_spec.hpp"

#include <memory>
#include <string_view>

namespace hofem {

/// A registered preconditioner; throws std::invalid_argument naming the valid choices.
std::unique_ptr<Preconditioner> make_preconditioner(std::string_view name);

/// The solver a spec names (resolved: not "auto"): CHOLMOD, UMFPACK, Eigen's
/// SimplicialLDLT, a Krylov method with a preconditioner, or hypre's own PCG
/// with BoomerAMG; with the spec's fixed iteration budget, which only a Krylov
/// solver takes (std::invalid_argument otherwise).
std::unique_ptr<LinearSolver> make_linear_solver(const SolverSpec& spec);
/// make_linear_solver(SolverSpec::parse(name)).
std::unique_ptr<LinearSolver> make_linear_solver(std::string_view name);

}  // namespace hofem
