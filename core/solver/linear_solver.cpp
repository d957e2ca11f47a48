#include "solver/linear_solver.hpp"

#include "solver/cholmod_solver.hpp"
#include "solver/hypre_pcg.hpp"
#include "solver/krylov.hpp"
#include "solver/umfpack_solver.hpp"

#include <Eigen/SparseCholesky>
#include <fmt/format.h>

#include <stdexcept>

namespace hofem {

namespace {

class EigenLdltSolver final : public LinearSolver {
 public:
  std::string_view name() const override { return "eigen-ldlt"; }
  void analyze(const SparseMatrix& A) override {
    ldlt_.analyzePattern(A);
    ++analyses_;
    pattern_ = pattern_fingerprint(A);
  }
  bool factorize(const SparseMatrix& A) override {
    if (analyses_ == 0 || pattern_fingerprint(A) != pattern_) analyze(A);
    ldlt_.factorize(A);
    ++factorizations_;
    if (ldlt_.info() != Eigen::Success) return false;
    // LDL^T succeeds on indefinite matrices; report them as not positive definite
    // like Cholesky does, so Newton treats both solvers alike.
    return (ldlt_.vectorD().array() > 0.0).all();
  }
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override { x = ldlt_.solve(b); }

 private:
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Upper> ldlt_;
  std::uint64_t pattern_ = 0;  // pattern_fingerprint of the analysed matrix
};

std::unique_ptr<LinearSolver> make_unbudgeted(const SolverSpec& spec) {
  if (!spec.method) throw std::logic_error("make_linear_solver: resolve \"auto\" first (resolve_linear_solver)");
  switch (*spec.method) {
    case SolverMethod::Cholmod: return std::make_unique<CholmodSolver>();
    case SolverMethod::EigenLdlt: return std::make_unique<EigenLdltSolver>();
    case SolverMethod::Umfpack: return std::make_unique<UmfpackSolver>();
    case SolverMethod::HyprePcg: return std::make_unique<HyprePcgSolver>();
    case SolverMethod::Cg:
    case SolverMethod::Cr:
    case SolverMethod::Minres:
    case SolverMethod::Gmres: return std::make_unique<KrylovSolver>(*spec.method, spec.preconditioner, spec.krylov);
  }
  throw std::logic_error("make_linear_solver: unknown SolverMethod");
}

}  // namespace

void apply_iteration_budget(LinearSolver& solver, int k) {
  if (k > 0 && !solver.set_fixed_iterations(k))
    throw std::invalid_argument(fmt::format("krylov_iterations = {} needs a Krylov solver, not {}", k, solver.name()));
}

std::unique_ptr<LinearSolver> make_linear_solver(const SolverSpec& spec) {
  std::unique_ptr<LinearSolver> solver = make_unbudgeted(spec);
  apply_iteration_budget(*solver, spec.fixed_iterations);
  return solver;
}

std::unique_ptr<LinearSolver> make_linear_solver(std::string_view name) {
  return make_linear_solver(SolverSpec::parse(name));
}

}  // namespace hofem
