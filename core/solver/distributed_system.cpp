#include "solver/distributed_system.hpp"

#include "assembly/mesh_view.hpp"

#include "parallel/collectives.hpp"
#include "parallel/mpi_runtime.hpp"
#include "linalg/boomeramg.hpp"
#include "linalg/hypre_matrix.hpp"

#include <Eigen/Geometry>
#include <HYPRE_krylov.h>
#include <HYPRE_parcsr_ls.h>
#include <_hypre_parcsr_mv.h>  // hypre_ParCSRMatrixDiag/Offd: the local blocks' sizes, for statistics only
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>

namespace hofem {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

}  // namespace

struct DistributedLinearSystem::Hypre {
  HYPRE_IJMatrix ij = nullptr;
  HYPRE_ParCSRMatrix parcsr = nullptr;
  HypreVector b, x;
  std::unique_ptr<BoomerAmg> amg;
  HYPRE_Solver krylov = nullptr;
  bool gmres = false;
  ~Hypre() { destroy(); }
  void destroy() {
    if (krylov) gmres ? HYPRE_ParCSRGMRESDestroy(krylov) : HYPRE_ParCSRPCGDestroy(krylov);
    krylov = nullptr;
    amg.reset();
    if (ij) HYPRE_IJMatrixDestroy(ij);
    ij = nullptr;
    parcsr = nullptr;
  }
};

DistributedLinearSystem::DistributedLinearSystem(const DistributedDofs& rows, DistributedSolverOptions options)
    : rows_(rows), options_(std::move(options)), hypre_(std::make_unique<Hypre>()) {
  ensure_hypre();
  validate(options_);
}

DistributedLinearSystem::~DistributedLinearSystem() = default;

void DistributedLinearSystem::set_coordinates(const Mesh& mesh, const DofMap& dofs) {
  if (!options_.rigid_body_modes) return;
  const auto n = static_cast<Eigen::Index>(rows_.row.size());
  if (dofs.num_free() != n || dofs.num_dofs() != 3 * mesh.num_nodes())
    throw std::invalid_argument(fmt::format("DistributedLinearSystem: a DOF map of {} free DOFs for {} rows",
                                            dofs.num_free(), n));
  // One centre for all ranks (the owned DOFs' global centroid): each rank's rows
  // of the same rotation then form one global vector.
  Eigen::Vector4d sums = Eigen::Vector4d::Zero();
  for (Eigen::Index i = 0; i < n; ++i)
    if (rows_.free.owned(static_cast<int>(i))) sums += mesh.nodes.col(dofs.free_dofs()[i] / 3).homogeneous();
  sum_over_ranks(sums, rows_.free.comm());
  const Eigen::Vector3d centre = sums.head<3>() / std::max(sums[3], 1.0);
  const Eigen::MatrixXd local = rigid_rotations({&mesh, &dofs, nullptr}, &centre);
  modes_.resize(rows_.owned_rows, 3);
  for (Eigen::Index i = 0; i < n; ++i)
    if (rows_.free.owned(static_cast<int>(i))) modes_.row(rows_.row[i] - rows_.first_row) = local.row(i);
}

void DistributedLinearSystem::assemble_matrix(const SparseMatrix& K_local) {
  const auto t0 = Clock::now();
  const auto n = static_cast<Eigen::Index>(rows_.row.size());
  if (K_local.rows() != n || K_local.cols() != n)
    throw std::invalid_argument(fmt::format("DistributedLinearSystem: a {}x{} matrix for {} local free DOFs",
                                            K_local.rows(), K_local.cols(), n));
  Hypre& h = *hypre_;
  h.destroy();  // a new matrix each time: see HypreMatrix::assign for why that is cheaper than re-opening
  const MPI_Comm comm = rows_.free.comm();
  const HYPRE_BigInt lo = rows_.first_row, hi = rows_.first_row + rows_.owned_rows - 1;
  hypre_check(HYPRE_IJMatrixCreate(comm, lo, hi, lo, hi, &h.ij), "HYPRE_IJMatrixCreate");
  hypre_check(HYPRE_IJMatrixSetObjectType(h.ij, HYPRE_PARCSR), "HYPRE_IJMatrixSetObjectType");
  hypre_check(HYPRE_IJMatrixInitialize(h.ij), "HYPRE_IJMatrixInitialize");
  // The matrix is symmetric (a Hessian of an energy, plus mass) and stored in
  // full, so column j is row j; GMRES is offered for its robustness, not for
  // nonsymmetric matrices, which this transposing copy would not handle. Only the
  // values this rank's elements produced (non-zero) are sent: rows of other
  // ranks are its ghost rows, shipped by Assemble.
  std::vector<HYPRE_BigInt> cols;
  std::vector<double> values;
  for (Eigen::Index j = 0; j < n; ++j) {
    cols.clear();
    values.clear();
    for (SparseMatrix::InnerIterator it(K_local, j); it; ++it)
      if (it.value() != 0.0) {
        cols.push_back(rows_.row[it.row()]);
        values.push_back(it.value());
      }
    if (cols.empty()) continue;
    HYPRE_Int count = static_cast<HYPRE_Int>(cols.size());
    HYPRE_BigInt row = rows_.row[j];
    hypre_check(HYPRE_IJMatrixAddToValues(h.ij, 1, &count, &row, cols.data(), values.data()),
                "HYPRE_IJMatrixAddToValues");
  }
  hypre_check(HYPRE_IJMatrixAssemble(h.ij), "HYPRE_IJMatrixAssemble");
  timings_.ij_seconds += since(t0);
  const auto t_amg = Clock::now();
  void* object = nullptr;
  hypre_check(HYPRE_IJMatrixGetObject(h.ij, &object), "HYPRE_IJMatrixGetObject");
  h.parcsr = static_cast<HYPRE_ParCSRMatrix>(object);
  h.b.conform(h.parcsr);
  h.x.conform(h.parcsr);
  BoomerAmgOptions amg = boomeramg_options(options_.amg);  // 3 functions per node (boomeramg.hpp)
  if (options_.rigid_body_modes) {
    if (modes_.rows() != rows_.owned_rows)
      throw std::logic_error("DistributedLinearSystem: rigid-body modes need set_coordinates() first");
    amg.interp_vec_variant = 2;  // GM-2, with nodal coarsening (row-sum block norm): boomeramg.cpp
    amg.nodal = 4;
  }
  h.amg = std::make_unique<BoomerAmg>(amg);
  h.x.set_zero();
  h.amg->setup(h.parcsr, h.b.par(), h.x.par(), options_.rigid_body_modes ? &modes_ : nullptr);
  h.gmres = options_.krylov == "gmres";
  if (h.gmres) {
    hypre_check(HYPRE_ParCSRGMRESCreate(comm, &h.krylov), "HYPRE_ParCSRGMRESCreate");
    hypre_check(HYPRE_ParCSRGMRESSetKDim(h.krylov, options_.gmres_restart), "HYPRE_ParCSRGMRESSetKDim");
    hypre_check(HYPRE_ParCSRGMRESSetAbsoluteTol(h.krylov, 0.0), "HYPRE_ParCSRGMRESSetAbsoluteTol");
    hypre_check(HYPRE_ParCSRGMRESSetPrintLevel(h.krylov, 0), "HYPRE_ParCSRGMRESSetPrintLevel");
    hypre_check(HYPRE_ParCSRGMRESSetPrecond(h.krylov, HYPRE_BoomerAMGSolve, BoomerAmg::already_set_up, h.amg->handle()),
                "HYPRE_ParCSRGMRESSetPrecond");
    hypre_check(HYPRE_ParCSRGMRESSetup(h.krylov, h.parcsr, h.b.par(), h.x.par()), "HYPRE_ParCSRGMRESSetup");
  } else {
    hypre_check(HYPRE_ParCSRPCGCreate(comm, &h.krylov), "HYPRE_ParCSRPCGCreate");
    hypre_check(HYPRE_ParCSRPCGSetTwoNorm(h.krylov, 1), "HYPRE_ParCSRPCGSetTwoNorm");  // ||r||_2 <= rtol ||b||_2
    hypre_check(HYPRE_ParCSRPCGSetAbsoluteTol(h.krylov, 0.0), "HYPRE_ParCSRPCGSetAbsoluteTol");
    hypre_check(HYPRE_ParCSRPCGSetPrintLevel(h.krylov, 0), "HYPRE_ParCSRPCGSetPrintLevel");
    hypre_check(HYPRE_ParCSRPCGSetPrecond(h.krylov, HYPRE_BoomerAMGSolve, BoomerAmg::already_set_up, h.amg->handle()),
                "HYPRE_ParCSRPCGSetPrecond");
    hypre_check(HYPRE_ParCSRPCGSetup(h.krylov, h.parcsr, h.b.par(), h.x.par()), "HYPRE_ParCSRPCGSetup");
  }
  timings_.amg_seconds += since(t_amg);
  ++timings_.setups;
}

long long DistributedLinearSystem::local_nonzeros() const {
  if (!hypre_->parcsr) return 0;
  auto* A = reinterpret_cast<hypre_ParCSRMatrix*>(hypre_->parcsr);
  return static_cast<long long>(hypre_CSRMatrixNumNonzeros(hypre_ParCSRMatrixDiag(A))) +
         hypre_CSRMatrixNumNonzeros(hypre_ParCSRMatrixOffd(A));
}

long long DistributedLinearSystem::matvec_receive_values() const {
  if (!hypre_->parcsr) return 0;
  return hypre_CSRMatrixNumCols(hypre_ParCSRMatrixOffd(reinterpret_cast<hypre_ParCSRMatrix*>(hypre_->parcsr)));
}

DistributedSolveResult DistributedLinearSystem::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x, double rtol,
                                                      int max_iterations) {
  Hypre& h = *hypre_;
  if (!h.krylov) throw std::logic_error("DistributedLinearSystem: solve before assemble_matrix");
  const auto n = static_cast<Eigen::Index>(rows_.row.size());
  if (b.size() != n)
    throw std::invalid_argument(fmt::format("DistributedLinearSystem: right-hand side of {} for {} local free DOFs",
                                            b.size(), n));
  DistributedSolveResult r;
  const auto t1 = Clock::now();
  Eigen::VectorXd mine(rows_.owned_rows);
  for (Eigen::Index i = 0; i < n; ++i)
    if (rows_.free.owned(static_cast<int>(i))) mine[rows_.row[i] - rows_.first_row] = b[i];
  h.b.set(mine);
  h.x.set_zero();
  HYPRE_Int code = 0, its = 0;
  if (h.gmres) {
    hypre_check(HYPRE_ParCSRGMRESSetTol(h.krylov, rtol), "HYPRE_ParCSRGMRESSetTol");
    hypre_check(HYPRE_ParCSRGMRESSetMaxIter(h.krylov, max_iterations), "HYPRE_ParCSRGMRESSetMaxIter");
    code = HYPRE_ParCSRGMRESSolve(h.krylov, h.parcsr, h.b.par(), h.x.par());
    HYPRE_ParCSRGMRESGetNumIterations(h.krylov, &its);
    HYPRE_ParCSRGMRESGetFinalRelativeResidualNorm(h.krylov, &r.relative_residual);
  } else {
    hypre_check(HYPRE_ParCSRPCGSetTol(h.krylov, rtol), "HYPRE_ParCSRPCGSetTol");
    hypre_check(HYPRE_ParCSRPCGSetMaxIter(h.krylov, max_iterations), "HYPRE_ParCSRPCGSetMaxIter");
    code = HYPRE_ParCSRPCGSolve(h.krylov, h.parcsr, h.b.par(), h.x.par());
    HYPRE_ParCSRPCGGetNumIterations(h.krylov, &its);
    HYPRE_ParCSRPCGGetFinalRelativeResidualNorm(h.krylov, &r.relative_residual);
  }
  if (code != 0) HYPRE_ClearAllErrors();  // non-convergence is reported below, not thrown
  r.iterations = its;
  r.converged = r.relative_residual <= rtol;
  if (!r.converged)
    r.message = fmt::format("hypre {} + BoomerAMG: relative residual {:.3g} after {} iterations (target {:.3g})",
                            options_.krylov, r.relative_residual, its, rtol);
  h.x.get(mine);
  x.setZero(n);
  for (Eigen::Index i = 0; i < n; ++i)
    if (rows_.free.owned(static_cast<int>(i))) x[i] = mine[rows_.row[i] - rows_.first_row];
  rows_.free.update_ghosts(x);
  r.solve_seconds = since(t1);
  ++timings_.solves;
  timings_.iterations += its;
  timings_.krylov_seconds += r.solve_seconds;
  return r;
}

DistributedHypreSolver::DistributedHypreSolver(const DistributedDofs& rows, DistributedSolverOptions options)
    : system_(rows, std::move(options)),
      name_(fmt::format("distributed hypre-{}+{}{}", system_.options().krylov, system_.options().amg,
                        system_.options().rigid_body_modes ? "+rigid" : "")) {}

bool DistributedHypreSolver::factorize(const SparseMatrix& A) {
  error_.clear();
  // Every rank must agree (the set-up is collective): a non-finite entry anywhere stops all.
  if (any_rank(!A.coeffs().allFinite(), system_.rows().free.comm())) {
    error_ = fmt::format("{}: the matrix has non-finite entries", name_);
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
