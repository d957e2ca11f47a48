#include "solver/solver_registry.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

#include "linalg/boomeramg_variants.hpp"

namespace hofem {

namespace {

std::vector<PreconditionerEntry> make_preconditioner_rows() {
  using K = PreconditionerKind;
  std::vector<PreconditionerEntry> rows{
      {"none", "no preconditioner (M = I)", K::Identity},
      {"jacobi", "the inverse of A's diagonal", K::Jacobi},
      {"block-jacobi", "the inverses of A's 3x3 nodal diagonal blocks", K::BlockJacobi},
      {"ic0", "incomplete Cholesky with zero fill (thesis Algorithm 2), diagonal shift on breakdown", K::Ic0},
      {"eigen-ict", "Eigen's memory-limited incomplete Cholesky (Lin and More), natural ordering", K::EigenIct},
  };
  for (const BoomerAmgVariant& v : boomeramg_variants()) rows.push_back({v.name, v.description, K::BoomerAmg});
  rows.push_back(
      {"pmg", "p-multigrid V-cycle over the element orders (thesis §3.1.3), Chebyshev smoothing, BoomerAMG at order 1",
       K::PMultigrid, true});
  rows.push_back(
      {"schwarz",
       "element-block Additive Schwarz (Longva et al. 2020 §5.2) on the selected cells, the diagonal elsewhere",
       K::Schwarz, true});
  return rows;
}

const std::vector<PreconditionerEntry>& preconditioner_rows() {
  static const std::vector<PreconditionerEntry> rows = make_preconditioner_rows();
  return rows;
}

std::vector<LinearSolverEntry> make_solver_rows() {
  const std::vector<std::string> all = preconditioner_names();
  return {
      {SolverMethod::Cholmod, "CHOLMOD supernodal Cholesky (SuiteSparse)", {}},
      {SolverMethod::Umfpack, "UMFPACK sparse LU (SuiteSparse), for nonsingular indefinite systems", {}},
      {SolverMethod::EigenLdlt, "Eigen's SimplicialLDLT (comparison, small problems)", {}},
      {SolverMethod::HyprePcg, "hypre's PCG with BoomerAMG", {"amg"}},
      {SolverMethod::Cg, "conjugate gradients (thesis Algorithm 4)", all},
      {SolverMethod::Cr, "conjugate residuals (thesis Algorithm 5)", all},
      {SolverMethod::Minres, "MINRES (Paige and Saunders 1975)", all},
      {SolverMethod::Gmres, "restarted GMRES(m) (thesis Algorithm 6)", all},
  };
}

const std::vector<LinearSolverEntry>& solver_rows() {
  static const std::vector<LinearSolverEntry> rows = make_solver_rows();
  return rows;
}

}  // namespace

std::span<const PreconditionerEntry> preconditioner_registry() { return preconditioner_rows(); }

const PreconditionerEntry* find_preconditioner(std::string_view name) {
  for (const PreconditionerEntry& e : preconditioner_rows())
    if (e.name == name) return &e;
  return nullptr;
}

std::vector<std::string> preconditioner_names() {
  std::vector<std::string> names;
  for (const PreconditionerEntry& e : preconditioner_rows()) names.emplace_back(e.name);
  return names;
}

bool preconditioner_needs_mesh_view(std::string_view name) {
  const PreconditionerEntry* e = find_preconditioner(name);
  return e != nullptr && e->needs_mesh_view;
}

std::span<const LinearSolverEntry> linear_solver_registry() { return solver_rows(); }

std::vector<std::string> linear_solver_names() {
  std::vector<std::string> names;
  for (const LinearSolverEntry& e : solver_rows()) {
    const std::string method(method_name(e.method));
    if (e.preconditioners.empty()) names.push_back(method);
    for (const std::string& pc : e.preconditioners) names.push_back(method + "+" + pc);
  }
  return names;
}

std::string linear_solver_choices() {
  std::vector<std::string> single, krylov;
  for (const LinearSolverEntry& e : solver_rows()) {
    const std::string method(method_name(e.method));
    if (is_krylov_method(e.method))
      krylov.push_back(method);
    else if (e.preconditioners.empty())
      single.push_back(method);
    else
      for (const std::string& pc : e.preconditioners) single.push_back(method + "+" + pc);
  }
  return fmt::format("auto, {}, or <{}>+<{}>", fmt::join(single, ", "), fmt::join(krylov, "|"),
                     fmt::join(preconditioner_names(), "|"));
}

}  // namespace hofem
