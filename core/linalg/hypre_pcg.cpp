#include "linalg/hypre_pcg.hpp"

#include "linalg/boomeramg.hpp"
#include "linalg/hypre_matrix.hpp"
#include "linalg/solver_method.hpp"

#include <HYPRE_parcsr_ls.h>
#include <HYPRE_utilities.h>
#include <fmt/format.h>

#include <cmath>
#include <stdexcept>
#include <utility>

namespace hofem {

namespace {

// hypre's PCG stops on its recursively updated residual, which drifts from
// b - A x by rounding (~eps ||A|| ||x|| per iteration); when the true residual
// misses the target, PCG is re-run from its last iterate (a restart) at most this
// often. A target below that rounding level is never met: the solve then throws.
constexpr int kMaxRestarts = 2;

}  // namespace

struct HyprePcgSolver::Impl {
  explicit Impl(std::unique_ptr<BoomerAmgPreconditioner> amg) : M(std::move(amg)) {}
  ~Impl() { destroy_pcg(); }
  void destroy_pcg() {
    if (pcg) HYPRE_ParCSRPCGDestroy(pcg);
    pcg = nullptr;
  }
  HYPRE_ParCSRMatrix A() const { return M->matrix().parcsr(); }

  std::unique_ptr<BoomerAmgPreconditioner> M;  // owns the ParCSR matrix and the BoomerAMG hierarchy
  HypreVector b, x, r;
  HYPRE_Solver pcg = nullptr;
  Eigen::Index rows = 0;
  bool ready = false;
};

HyprePcgSolver::HyprePcgSolver(std::unique_ptr<BoomerAmgPreconditioner> amg) {
  if (!amg) throw std::invalid_argument("HyprePcgSolver: no BoomerAMG preconditioner");
  name_ = std::string(method_name(SolverMethod::HyprePcg)) + "+" + std::string(amg->name());
  impl_ = std::make_unique<Impl>(std::move(amg));
}
HyprePcgSolver::~HyprePcgSolver() = default;

void HyprePcgSolver::analyze(const SparseMatrix&) { ++analyses_; }

void HyprePcgSolver::set_mesh_view(const MeshView& d) { impl_->M->set_mesh_view(d); }

bool HyprePcgSolver::factorize(const SparseMatrix& A) {
  ++factorizations_;
  Impl& s = *impl_;
  s.ready = false;
  error_.clear();
  s.destroy_pcg();  // it points at the hierarchy about to be replaced
  if (!s.M->setup(A)) {
    error_ = std::string(name()) + ": " + s.M->last_error();
    return false;
  }
  s.rows = A.rows();
  if (s.rows == 0) return s.ready = true;
  try {
    s.b.conform(s.A());
    s.x.conform(s.A());
    s.r.conform(s.A());
    MPI_Comm comm = MPI_COMM_NULL;
    hypre_check(HYPRE_ParCSRMatrixGetComm(s.A(), &comm), "HYPRE_ParCSRMatrixGetComm");
    hypre_check(HYPRE_ParCSRPCGCreate(comm, &s.pcg), "HYPRE_ParCSRPCGCreate");
    // Two-norm: stop when ||r||_2 <= tol ||b||_2, our criterion (the default
    // compares <C r, r> with <C b, b>, the preconditioned norm; HYPRE_krylov.h).
    hypre_check(HYPRE_ParCSRPCGSetTwoNorm(s.pcg, 1), "HYPRE_ParCSRPCGSetTwoNorm");
    hypre_check(HYPRE_ParCSRPCGSetAbsoluteTol(s.pcg, 0.0), "HYPRE_ParCSRPCGSetAbsoluteTol");
    hypre_check(HYPRE_ParCSRPCGSetPrintLevel(s.pcg, 0), "HYPRE_ParCSRPCGSetPrintLevel");
    hypre_check(HYPRE_ParCSRPCGSetPrecond(s.pcg, HYPRE_BoomerAMGSolve, BoomerAmg::already_set_up, s.M->amg().handle()),
                "HYPRE_ParCSRPCGSetPrecond");
    hypre_check(HYPRE_ParCSRPCGSetup(s.pcg, s.A(), s.b.par(), s.x.par()), "HYPRE_ParCSRPCGSetup");
  } catch (const std::exception& e) {
    s.destroy_pcg();
    error_ = std::string(name()) + ": " + e.what();
    return false;
  }
  return s.ready = true;
}

void HyprePcgSolver::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  Impl& s = *impl_;
  if (!s.ready) throw std::logic_error("hypre-pcg+amg: solve without a successful factorize");
  if (b.size() != s.rows)
    throw std::invalid_argument(fmt::format("hypre-pcg+amg: right-hand side of {} for {} rows", b.size(), s.rows));
  last_ = {};
  x.setZero(s.rows);
  const double b_norm = b.norm();
  if (b_norm == 0.0) {  // x = 0 exactly; hypre would return it too
    last_.converged = true;
    return;
  }
  s.b.set(b);
  s.x.set_zero();
  hypre_check(HYPRE_ParCSRPCGSetTol(s.pcg, rtol_), "HYPRE_ParCSRPCGSetTol");
  std::string hypre_note;
  for (int attempt = 0;; ++attempt) {
    hypre_check(HYPRE_ParCSRPCGSetMaxIter(s.pcg, max_iterations_ - last_.iterations), "HYPRE_ParCSRPCGSetMaxIter");
    // Non-zero on non-convergence (HYPRE_ERROR_CONV) or breakdown; the verdict
    // below is on the true residual either way.
    const HYPRE_Int code = HYPRE_ParCSRPCGSolve(s.pcg, s.A(), s.b.par(), s.x.par());
    if (code != 0) {
      char description[256] = {};
      HYPRE_DescribeError(code, description);
      hypre_note = fmt::format(" (hypre: {})", description);
      HYPRE_ClearAllErrors();
    }
    HYPRE_Int iterations = 0;
    hypre_check(HYPRE_ParCSRPCGGetNumIterations(s.pcg, &iterations), "HYPRE_ParCSRPCGGetNumIterations");
    last_.iterations += iterations;
    // r = b - A x with hypre's own product, so that the check also holds on a
    // distributed matrix.
    hypre_check(HYPRE_ParVectorCopy(s.b.par(), s.r.par()), "HYPRE_ParVectorCopy");
    hypre_check(HYPRE_ParCSRMatrixMatvec(-1.0, s.A(), s.x.par(), 1.0, s.r.par()), "HYPRE_ParCSRMatrixMatvec");
    last_.relative_residual = std::sqrt(hypre_dot(s.r, s.r) / hypre_dot(s.b, s.b));
    last_.converged = last_.relative_residual <= rtol_;
    if (last_.converged || code != 0 || attempt == kMaxRestarts || last_.iterations >= max_iterations_) break;
  }
  s.x.get(x);
  if (!last_.converged)
    throw std::runtime_error(fmt::format("hypre-pcg+amg: no convergence ({} iterations, relative residual {:.3e}){}",
                                         last_.iterations, last_.relative_residual, hypre_note));
}

}  // namespace hofem
