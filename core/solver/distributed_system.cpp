#include "solver/distributed_system.hpp"

#include "parallel/mpi_runtime.hpp"
#include "solver/boomeramg.hpp"
#include "solver/hypre_matrix.hpp"

#include <HYPRE_krylov.h>
#include <HYPRE_parcsr_ls.h>
#include <fmt/format.h>

#include <chrono>
#include <stdexcept>

namespace hofem {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// BoomerAMG is set up before PCG's set-up, which then calls this in its place.
HYPRE_Int already_set_up(HYPRE_Solver, HYPRE_ParCSRMatrix, HYPRE_ParVector, HYPRE_ParVector) { return 0; }

}  // namespace

struct DistributedLinearSystem::Hypre {
  HYPRE_IJMatrix ij = nullptr;
  HYPRE_ParCSRMatrix parcsr = nullptr;
  HypreVector b, x;
  std::unique_ptr<BoomerAmg> amg;
  HYPRE_Solver pcg = nullptr;
  ~Hypre() { destroy(); }
  void destroy() {
    if (pcg) HYPRE_ParCSRPCGDestroy(pcg);
    pcg = nullptr;
    amg.reset();
    if (ij) HYPRE_IJMatrixDestroy(ij);
    ij = nullptr;
    parcsr = nullptr;
  }
};

DistributedLinearSystem::DistributedLinearSystem(MPI_Comm comm, DistributedDofs rows, const DofMap& dofs)
    : comm_(comm), rows_(std::move(rows)), hypre_(std::make_unique<Hypre>()) {
  ensure_hypre();
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
  if (rows_.parts != size_)
    throw std::invalid_argument(
        fmt::format("DistributedLinearSystem: the numbering has {} parts for {} ranks", rows_.parts, size_));
  if (rows_.first_row.back() != dofs.num_free())
    throw std::invalid_argument(fmt::format("DistributedLinearSystem: the numbering has {} rows for {} free DOFs",
                                            rows_.first_row.back(), dofs.num_free()));
  row_of_free_.resize(dofs.num_free());
  for (int i = 0; i < dofs.num_free(); ++i) row_of_free_[i] = rows_.global_row[dofs.free_dofs()[i]];
}

DistributedLinearSystem::~DistributedLinearSystem() = default;

double DistributedLinearSystem::assemble_matrix(const SparseMatrix& K_local) {
  const auto t0 = Clock::now();
  const auto n = static_cast<Eigen::Index>(row_of_free_.size());
  if (K_local.rows() != n || K_local.cols() != n)
    throw std::invalid_argument(fmt::format("DistributedLinearSystem: a {}x{} matrix for {} free DOFs", K_local.rows(),
                                            K_local.cols(), n));
  Hypre& h = *hypre_;
  h.destroy();  // a new matrix each time: see HypreMatrix::assign for why that is cheaper than re-opening
  const HYPRE_BigInt lo = rows_.first_row[rank_], hi = rows_.first_row[rank_ + 1] - 1;
  hypre_check(HYPRE_IJMatrixCreate(comm_, lo, hi, lo, hi, &h.ij), "HYPRE_IJMatrixCreate");
  hypre_check(HYPRE_IJMatrixSetObjectType(h.ij, HYPRE_PARCSR), "HYPRE_IJMatrixSetObjectType");
  hypre_check(HYPRE_IJMatrixInitialize(h.ij), "HYPRE_IJMatrixInitialize");
  // The matrix is symmetric and stored in full, so column j is row j. Only the
  // values this rank's elements produced (non-zero) are sent: rows of other
  // ranks are its ghost rows, shipped by Assemble.
  std::vector<HYPRE_BigInt> cols;
  std::vector<double> values;
  for (Eigen::Index j = 0; j < n; ++j) {
    cols.clear();
    values.clear();
    for (SparseMatrix::InnerIterator it(K_local, j); it; ++it)
      if (it.value() != 0.0) {
        cols.push_back(row_of_free_[it.row()]);
        values.push_back(it.value());
      }
    if (cols.empty()) continue;
    HYPRE_Int count = static_cast<HYPRE_Int>(cols.size());
    HYPRE_BigInt row = row_of_free_[j];
    hypre_check(HYPRE_IJMatrixAddToValues(h.ij, 1, &count, &row, cols.data(), values.data()),
                "HYPRE_IJMatrixAddToValues");
  }
  hypre_check(HYPRE_IJMatrixAssemble(h.ij), "HYPRE_IJMatrixAssemble");
  void* object = nullptr;
  hypre_check(HYPRE_IJMatrixGetObject(h.ij, &object), "HYPRE_IJMatrixGetObject");
  h.parcsr = static_cast<HYPRE_ParCSRMatrix>(object);
  h.b.conform(h.parcsr);
  h.x.conform(h.parcsr);
  BoomerAmgOptions options;  // 3 functions per node, HMIS + extended+i (boomeramg.hpp)
  h.amg = std::make_unique<BoomerAmg>(options);
  h.x.set_zero();
  h.amg->setup(h.parcsr, h.b.par(), h.x.par());
  hypre_check(HYPRE_ParCSRPCGCreate(comm_, &h.pcg), "HYPRE_ParCSRPCGCreate");
  hypre_check(HYPRE_ParCSRPCGSetTwoNorm(h.pcg, 1), "HYPRE_ParCSRPCGSetTwoNorm");  // ||r||_2 <= rtol ||b||_2
  hypre_check(HYPRE_ParCSRPCGSetAbsoluteTol(h.pcg, 0.0), "HYPRE_ParCSRPCGSetAbsoluteTol");
  hypre_check(HYPRE_ParCSRPCGSetPrintLevel(h.pcg, 0), "HYPRE_ParCSRPCGSetPrintLevel");
  hypre_check(HYPRE_ParCSRPCGSetPrecond(h.pcg, HYPRE_BoomerAMGSolve, already_set_up, h.amg->handle()),
              "HYPRE_ParCSRPCGSetPrecond");
  hypre_check(HYPRE_ParCSRPCGSetup(h.pcg, h.parcsr, h.b.par(), h.x.par()), "HYPRE_ParCSRPCGSetup");
  return since(t0);
}

long long DistributedLinearSystem::local_nonzeros() const {
  // Counted on demand (a statistic, not worth a pass over the rows per assembly).
  if (!hypre_->parcsr) return 0;
  long long count = 0;
  for (HYPRE_BigInt r = rows_.first_row[rank_]; r < rows_.first_row[rank_ + 1]; ++r) {
    HYPRE_Int size = 0;
    HYPRE_BigInt* c = nullptr;
    double* v = nullptr;
    hypre_check(HYPRE_ParCSRMatrixGetRow(hypre_->parcsr, r, &size, &c, &v), "HYPRE_ParCSRMatrixGetRow");
    count += size;
    hypre_check(HYPRE_ParCSRMatrixRestoreRow(hypre_->parcsr, r, &size, &c, &v), "HYPRE_ParCSRMatrixRestoreRow");
  }
  return count;
}

DistributedSolveResult DistributedLinearSystem::assemble_and_solve(const SparseMatrix& K_local,
                                                                   const Eigen::VectorXd& b_local, Eigen::VectorXd& x,
                                                                   double rtol) {
  const auto n = static_cast<Eigen::Index>(row_of_free_.size());
  if (b_local.size() != n)
    throw std::invalid_argument(fmt::format("DistributedLinearSystem: {} values for {} free DOFs", b_local.size(), n));
  const double setup = assemble_matrix(K_local);
  Eigen::VectorXd b(n);
  MPI_Allreduce(b_local.data(), b.data(), static_cast<int>(n), MPI_DOUBLE, MPI_SUM, comm_);
  DistributedSolveResult r = solve(b, x, rtol);
  r.setup_seconds += setup;
  return r;
}

DistributedSolveResult DistributedLinearSystem::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x, double rtol,
                                                      int max_iterations) {
  Hypre& h = *hypre_;
  if (!h.pcg) throw std::logic_error("DistributedLinearSystem: solve before assemble_matrix");
  const auto n = static_cast<Eigen::Index>(row_of_free_.size());
  if (b.size() != n)
    throw std::invalid_argument(fmt::format("DistributedLinearSystem: right-hand side of {} for {} free DOFs", b.size(), n));
  DistributedSolveResult r;
  const auto t1 = Clock::now();
  Eigen::VectorXd mine(rows_.owned_rows(rank_));
  for (Eigen::Index i = 0; i < n; ++i)
    if (const int row = row_of_free_[i] - rows_.first_row[rank_]; row >= 0 && row < mine.size()) mine[row] = b[i];
  h.b.set(mine);
  h.x.set_zero();
  hypre_check(HYPRE_ParCSRPCGSetTol(h.pcg, rtol), "HYPRE_ParCSRPCGSetTol");
  hypre_check(HYPRE_ParCSRPCGSetMaxIter(h.pcg, max_iterations), "HYPRE_ParCSRPCGSetMaxIter");
  const HYPRE_Int code = HYPRE_ParCSRPCGSolve(h.pcg, h.parcsr, h.b.par(), h.x.par());
  HYPRE_Int its = 0;
  HYPRE_ParCSRPCGGetNumIterations(h.pcg, &its);
  HYPRE_ParCSRPCGGetFinalRelativeResidualNorm(h.pcg, &r.relative_residual);
  if (code != 0) HYPRE_ClearAllErrors();  // non-convergence is reported below, not thrown
  r.iterations = its;
  r.converged = r.relative_residual <= rtol;
  if (!r.converged)
    r.message = fmt::format("hypre PCG + BoomerAMG: relative residual {:.3g} after {} iterations (target {:.3g})",
                            r.relative_residual, its, rtol);
  // Every rank gets the whole solution, in the serial free numbering.
  h.x.get(mine);
  std::vector<int> counts(size_), displs(size_);
  for (int p = 0; p < size_; ++p) {
    counts[p] = rows_.owned_rows(p);
    displs[p] = rows_.first_row[p];
  }
  Eigen::VectorXd global(n);
  MPI_Allgatherv(mine.data(), counts[rank_], MPI_DOUBLE, global.data(), counts.data(), displs.data(), MPI_DOUBLE,
                 comm_);
  x.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) x[i] = global[row_of_free_[i]];
  r.solve_seconds = since(t1);
  return r;
}

DistributedHypreSolver::DistributedHypreSolver(MPI_Comm comm, DistributedDofs rows, const DofMap& dofs)
    : system_(comm, std::move(rows), dofs) {}

bool DistributedHypreSolver::factorize(const SparseMatrix& A) {
  error_.clear();
  if (!A.coeffs().allFinite()) {
    error_ = "distributed hypre-pcg+amg: the matrix has non-finite entries";
    return false;
  }
  system_.assemble_matrix(A);
  ++factorizations_;
  return true;
}

void DistributedHypreSolver::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  last_ = system_.solve(b, x, rtol_);
  if (!last_.converged) throw std::runtime_error(last_.message);
}

}  // namespace hofem
