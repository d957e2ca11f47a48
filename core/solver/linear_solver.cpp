#include "solver/linear_solver.hpp"

#include "solver/cholmod_solver.hpp"
#include "solver/hypre_pcg.hpp"
#include "solver/krylov.hpp"
#include "solver/umfpack_solver.hpp"

#include <Eigen/SparseCholesky>
#include <fmt/format.h>
#include <fmt/ranges.h>

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

}  // namespace

std::unique_ptr<LinearSolver> make_linear_solver(std::string_view name) {
  if (name == "cholmod") return std::make_unique<CholmodSolver>();
  if (name == "eigen-ldlt") return std::make_unique<EigenLdltSolver>();
  if (name == "umfpack") return std::make_unique<UmfpackSolver>();
  if (name == "hypre-pcg+amg") return make_hypre_pcg_solver();
  // "<krylov method>+<preconditioner>", e.g. "cg+ic0".
  if (const size_t plus = name.find('+'); plus != std::string_view::npos) {
    const std::string method(name.substr(0, plus)), pc(name.substr(plus + 1));
    if ((method == "cg" || method == "cr" || method == "minres" || method == "gmres"))
      return std::make_unique<KrylovSolver>(method, pc);
  }
  throw std::invalid_argument(fmt::format(
      "unknown linear solver '{}' (valid: cholmod, umfpack, eigen-ldlt, hypre-pcg+amg, or <cg|cr|minres|gmres>+<{}>)", name,
      fmt::join(preconditioner_names(), "|")));
}

}  // namespace hofem
