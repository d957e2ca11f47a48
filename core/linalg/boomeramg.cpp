#include "linalg/boomeramg.hpp"

#include "parallel/mpi_runtime.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace hofem {

// --- BoomerAmg on hypre objects ---------------------------------------------------

void BoomerAmg::reset() {
  if (solver_) HYPRE_BoomerAMGDestroy(solver_);
  solver_ = nullptr;
  mode_handles_.clear();
  modes_.clear();
}

void BoomerAmg::setup(HYPRE_ParCSRMatrix A, HYPRE_ParVector b, HYPRE_ParVector x, const Eigen::MatrixXd* modes) {
  // A fresh solver per set-up: hypre can re-run BoomerAMGSetup on a used solver,
  // but a new one costs nothing next to the set-up and carries nothing over.
  reset();
  const BoomerAmgOptions& o = options_;
  hypre_check(HYPRE_BoomerAMGCreate(&solver_), "HYPRE_BoomerAMGCreate");
  auto set = [](HYPRE_Int code, const char* what) { hypre_check(code, what); };
  // As a preconditioner: tolerance 0 and one iteration, i.e. exactly one V-cycle
  // (HYPRE_parcsr_ls.h, SetTol and SetMaxIter). With 3 functions and no DofFunc,
  // unknown i belongs to function i % 3 (SetDofFunc): our node-interleaved order.
  set(HYPRE_BoomerAMGSetPrintLevel(solver_, 0), "HYPRE_BoomerAMGSetPrintLevel");
  set(HYPRE_BoomerAMGSetTol(solver_, 0.0), "HYPRE_BoomerAMGSetTol");
  set(HYPRE_BoomerAMGSetMaxIter(solver_, 1), "HYPRE_BoomerAMGSetMaxIter");
  set(HYPRE_BoomerAMGSetNumFunctions(solver_, o.num_functions), "HYPRE_BoomerAMGSetNumFunctions");
  set(HYPRE_BoomerAMGSetCoarsenType(solver_, o.coarsen_type), "HYPRE_BoomerAMGSetCoarsenType");
  set(HYPRE_BoomerAMGSetInterpType(solver_, o.interp_type), "HYPRE_BoomerAMGSetInterpType");
  set(HYPRE_BoomerAMGSetPMaxElmts(solver_, o.p_max_elmts), "HYPRE_BoomerAMGSetPMaxElmts");
  set(HYPRE_BoomerAMGSetStrongThreshold(solver_, o.strong_threshold), "HYPRE_BoomerAMGSetStrongThreshold");
  set(HYPRE_BoomerAMGSetNumSweeps(solver_, o.num_sweeps), "HYPRE_BoomerAMGSetNumSweeps");
  set(HYPRE_BoomerAMGSetCycleRelaxType(solver_, o.relax_down, 1), "HYPRE_BoomerAMGSetCycleRelaxType(down)");
  set(HYPRE_BoomerAMGSetCycleRelaxType(solver_, o.relax_up, 2), "HYPRE_BoomerAMGSetCycleRelaxType(up)");
  set(HYPRE_BoomerAMGSetCycleRelaxType(solver_, o.relax_coarse, 3), "HYPRE_BoomerAMGSetCycleRelaxType(coarsest)");
  // Lexicographic order in both sweeps: the up sweep then is the exact adjoint of
  // the down sweep and the V-cycle a symmetric operator (CG needs one).
  set(HYPRE_BoomerAMGSetRelaxOrder(solver_, 0), "HYPRE_BoomerAMGSetRelaxOrder");
  if (o.nodal > 0) set(HYPRE_BoomerAMGSetNodal(solver_, o.nodal), "HYPRE_BoomerAMGSetNodal");
  if (o.agg_num_levels > 0) {
    set(HYPRE_BoomerAMGSetAggNumLevels(solver_, o.agg_num_levels), "HYPRE_BoomerAMGSetAggNumLevels");
    set(HYPRE_BoomerAMGSetAggInterpType(solver_, o.agg_interp_type), "HYPRE_BoomerAMGSetAggInterpType");
    set(HYPRE_BoomerAMGSetAggPMaxElmts(solver_, o.agg_p_max_elmts), "HYPRE_BoomerAMGSetAggPMaxElmts");
    set(HYPRE_BoomerAMGSetNumPaths(solver_, o.num_paths), "HYPRE_BoomerAMGSetNumPaths");
  }
  if (o.interp_vec_variant > 0) {
    if (!modes || modes->cols() == 0) throw std::runtime_error("interpolation vectors requested but none given");
    for (Eigen::Index k = 0; k < modes->cols(); ++k) {
      modes_.push_back(std::make_unique<HypreVector>());
      modes_.back()->conform(A);
      modes_.back()->set(modes->col(k));
      mode_handles_.push_back(modes_.back()->par());
    }
    set(HYPRE_BoomerAMGSetInterpVectors(solver_, static_cast<HYPRE_Int>(mode_handles_.size()), mode_handles_.data()),
        "HYPRE_BoomerAMGSetInterpVectors");
    set(HYPRE_BoomerAMGSetInterpVecVariant(solver_, o.interp_vec_variant), "HYPRE_BoomerAMGSetInterpVecVariant");
    set(HYPRE_BoomerAMGSetInterpVecQMax(solver_, o.interp_vec_q_max), "HYPRE_BoomerAMGSetInterpVecQMax");
  }
  hypre_check(HYPRE_BoomerAMGSetup(solver_, A, b, x), "HYPRE_BoomerAMGSetup");
}

void BoomerAmg::apply(HYPRE_ParCSRMatrix A, HYPRE_ParVector b, HYPRE_ParVector x) const {
  if (!solver_) throw std::logic_error("BoomerAmg::apply before setup");
  hypre_check(HYPRE_ParVectorSetConstantValues(x, 0.0), "HYPRE_ParVectorSetConstantValues");
  hypre_check(HYPRE_BoomerAMGSolve(solver_, A, b, x), "HYPRE_BoomerAMGSolve");
}

// --- The Preconditioner on our serial matrices -------------------------------------

void BoomerAmgPreconditioner::set_row_layout(std::vector<int> row_dofs, Eigen::MatrixXd modes) {
  row_dofs_ = std::move(row_dofs);
  modes_ = std::move(modes);
  has_layout_ = true;
}

bool BoomerAmgPreconditioner::setup(const SparseMatrix& A) {
  ready_ = false;
  error_.clear();
  if (const std::string problem = check(A); !problem.empty()) return fail(std::string(name()) + ": " + problem);
  rows_ = A.rows();
  if (rows_ == 0) return ready_ = true;
  try {
    ensure_hypre();
    amg_.reset();  // the old hierarchy refers to the matrix about to be replaced
    A_.assign(A);
    b_.conform(A_.parcsr());
    x_.conform(A_.parcsr());
    amg_.setup(A_.parcsr(), b_.par(), x_.par(), &modes_);
  } catch (const std::exception& e) {
    return fail(std::string(name()) + ": " + e.what());
  }
  return ready_ = true;
}

void BoomerAmgPreconditioner::apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const {
  if (!ready_) throw std::logic_error(std::string(name()) + ": apply without a successful setup");
  if (r.size() != rows_) throw std::invalid_argument(fmt::format("{}: vector of {} for {} rows", name(), r.size(), rows_));
  if (rows_ == 0) return z.resize(0);
  b_.set(r);
  amg_.apply(A_.parcsr(), b_.par(), x_.par());
  x_.get(z);
}

std::string BoomerAmgPreconditioner::check(const SparseMatrix& A) const {
  if (std::string p = hypre_matrix_problem(A); !p.empty()) return p;
  const int nf = amg_.options().num_functions;
  if (A.rows() % nf != 0) return fmt::format("{} unknowns are not {} per node", A.rows(), nf);
  if (amg_.options().interp_vec_variant > 0 && !has_layout_)
    return "rigid-body modes need the mesh and DOF map (set_mesh_view)";
  if (!has_layout_ || nf != 3) return {};
  // hypre assigns unknown i to function i % num_functions: the free DOFs must be
  // whole nodes in x, y, z order (DofMap constrains whole nodes, so they are).
  const std::vector<int>& free = row_dofs_;
  if (static_cast<Eigen::Index>(free.size()) != A.rows())
    return fmt::format("DOF map has {} free DOFs, matrix {} rows", free.size(), A.rows());
  if (amg_.options().interp_vec_variant > 0 && modes_.rows() != A.rows())
    return fmt::format("{} rigid-body mode rows for {} matrix rows", modes_.rows(), A.rows());
  for (size_t i = 0; i < free.size(); ++i)
    if (free[i] % 3 != static_cast<int>(i % 3) || free[i] / 3 != free[i - i % 3] / 3)
      return fmt::format("free DOF {} (global {}) breaks the node-interleaved x, y, z layout", i, free[i]);
  return {};
}

}  // namespace hofem
