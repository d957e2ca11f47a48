#include "solver/boomeramg.hpp"

#include "parallel/mpi_runtime.hpp"

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <stdexcept>

namespace hofem {

// Measured 2026-11-22 on the machine of shared/machine.md (AMD EPYC Zen 5, 2 vCPU),
// hypre 2.26, one MPI rank. Unit cube clamped at x = 0, linear material E = 1,
// nu = 0.3, unit body force; our CG (solver/krylov.hpp) to ||b - A x|| <= 1e-8 ||b||
// from x = 0. Seconds are CPU time of the solving thread (the machine was shared,
// load 4-8: wall time was noise), best of 2-3 runs; they scatter by ~20 %.
//
//   system            N        variant          set-up s   CG its   solve s
//   P1 tet  n = 16    13,872   amg               0.096      17       0.093
//                              amg-nodal         0.135      20       0.119
//                              amg-aggressive    0.045      25       0.088
//                              hypre-pcg+amg     0.092      17       0.102
//   P2 tet  n = 8     13,872   amg               0.102      21       0.244
//                              amg-nodal         0.127      27       0.226
//                              amg-aggressive    0.052      33       0.220
//                              hypre-pcg+amg     0.121      21       0.222
//   Hex8    n = 16    13,872   amg               0.115      17       0.175
//                              amg-nodal         0.159      19       0.143
//                              amg-aggressive    0.047      22       0.139
//                              hypre-pcg+amg     0.087      17       0.119
//   P1 tet  n = 32   104,544   amg               0.995      19       1.967
//                              amg-nodal         1.179      22       1.976
//                              amg-aggressive    0.392      25       1.553
//                              hypre-pcg+amg     0.898      19       1.870
//   P2 tet  n = 16   104,544   amg               1.040      22       2.914
//                              amg-nodal         1.207      28       3.304
//                              amg-aggressive    0.448      34       2.798
//                              hypre-pcg+amg     0.946      22       2.987
//
// Why "amg" is the default (HYPRE_parcsr_ls.h for every parameter):
// - HMIS coarsening, extended+i interpolation truncated to 4 entries per row: hypre's
//   own defaults. PMIS (coarsen 8): 1-2 more iterations, 10-20 % cheaper cycles,
//   the same time within the scatter; Falgout (6): 1-2 fewer iterations, ~50 %
//   dearer cycles; classical (0) / extended (14) interpolation: 5-7 / 1 more
//   iterations; P_max 2: 5-7 more iterations.
// - Strength threshold 0.5, hypre's advice for 3D ("0.5 or 0.6"; "0.9 for
//   elasticity" did not help here: P2 n = 8 took 24 iterations at 0.9, 25 at 0.25,
//   21 at 0.5; 0.7 cuts the P1 set-up at n = 32 by 40 % but P2 n = 16 then takes
//   24 iterations instead of 22).
// - Smoother: l1 Gauss-Seidel forward on the way down (13), backward on the way up
//   (14), one sweep: the up sweep is the adjoint of the down sweep, so the V-cycle
//   is symmetric (test_mpi_hypre.cpp measures 3e-16) and CG-safe. Symmetric
//   Gauss-Seidel on both sides (8 or 6) saves 14-18 % of the iterations but doubles
//   the sweeps: P1 n = 32, 16 iterations in 2.62 s against 19 in 1.82 s. On one rank
//   l1 Gauss-Seidel is plain Gauss-Seidel; on many, the l1 term keeps the hybrid
//   (processor-block) sweep convergent (Baker, Falgout, Kolev, Yang 2011).
// - Systems AMG with unknown-based coarsening (NumFunctions 3) rather than nodal:
//   nodal coarsening (amg-nodal, row-sum block norm 4; Frobenius 1 was no better)
//   takes 3-6 more iterations; its cheaper cycle about evens the time out on P2
//   and does not on P1.
// - Standard rather than aggressive coarsening: aggressive coarsening on the first
//   level (amg-aggressive, multipass interpolation) sets up 2-2.5x faster and takes
//   18-34 % less time for set-up plus solve at nu = 0.3, but its iterations grow
//   fastest as the material stiffens: at nu = 0.45 (one run each), n = 32 P1 /
//   n = 16 P2 take 40 / 46 iterations against 24 / 27 for amg, and its time
//   advantage is gone (set-up + solve P1 3.45 s vs 3.29 s, P2 6.28 s vs 6.20 s).
//   amg-aggressive suits compressible materials and loose Newton tolerances. Two
//   aggressive levels: 32 / 45 iterations at nu = 0.3, faster for P1, slower for P2.
// - Rigid-body rotations as interpolation vectors (interp_vec_variant 2, GM-2, with
//   nodal coarsening, q_max 4) cut the iterations (n = 32 P1 22 -> 15, n = 16 P2
//   28 -> 18) but cost ~5 s of set-up and 2.4-3.3x the cycle: no named variant.
//   Variant 3, and q_max 2, made hypre's set-up fail on P1 n = 16 (reported by setup()).
// - hypre's PCG with the same V-cycle takes the same iterations as our CG and about
//   the same time: the cycle dominates either way.
// P3 (n = 10, 86,490 unknowns): 33 / 35 / 46 iterations for amg / nodal / aggressive.

BoomerAmgOptions boomeramg_options(std::string_view variant) {
  BoomerAmgOptions o;  // "amg": the defaults of BoomerAmgOptions, chosen above
  if (variant == "amg") return o;
  if (variant == "amg-nodal") {
    o.nodal = 4;  // row-sum norm of each node's 3x3 block
    return o;
  }
  if (variant == "amg-aggressive") {
    o.agg_num_levels = 1;  // multipass interpolation on that level (hypre's default)
    return o;
  }
  throw std::invalid_argument(fmt::format("unknown BoomerAMG variant '{}'", variant));
}

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

Eigen::MatrixXd rigid_rotations(const MeshView& d, const Eigen::Vector3d* given_centre) {
  const Eigen::Vector3d centre = given_centre ? *given_centre : Eigen::Vector3d(d.mesh->nodes.rowwise().mean());
  const std::vector<int>& free = d.dofs->free_dofs();
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(free.size()), 3);
  for (size_t i = 0; i < free.size(); ++i) {
    const int node = free[i] / 3, c = free[i] % 3;
    const Eigen::Vector3d X = d.mesh->nodes.col(node) - centre;
    for (int k = 0; k < 3; ++k) R(static_cast<Eigen::Index>(i), k) = Eigen::Vector3d::Unit(k).cross(X)[c];
  }
  return R;
}

// --- The Preconditioner on our serial matrices -------------------------------------

bool BoomerAmgPreconditioner::setup(const SparseMatrix& A) {
  ready_ = false;
  error_.clear();
  if (const std::string problem = check(A); !problem.empty()) return fail(name_ + ": " + problem);
  rows_ = A.rows();
  if (rows_ == 0) return ready_ = true;
  Eigen::MatrixXd modes;
  if (amg_.options().interp_vec_variant > 0) modes = rigid_rotations(mesh_view_);
  try {
    ensure_hypre();
    amg_.reset();  // the old hierarchy refers to the matrix about to be replaced
    A_.assign(A);
    b_.conform(A_.parcsr());
    x_.conform(A_.parcsr());
    amg_.setup(A_.parcsr(), b_.par(), x_.par(), &modes);
  } catch (const std::exception& e) {
    return fail(name_ + ": " + e.what());
  }
  return ready_ = true;
}

void BoomerAmgPreconditioner::apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const {
  if (!ready_) throw std::logic_error(name_ + ": apply without a successful setup");
  if (r.size() != rows_) throw std::invalid_argument(fmt::format("{}: vector of {} for {} rows", name_, r.size(), rows_));
  if (rows_ == 0) return z.resize(0);
  b_.set(r);
  amg_.apply(A_.parcsr(), b_.par(), x_.par());
  x_.get(z);
}

std::string BoomerAmgPreconditioner::check(const SparseMatrix& A) const {
  if (std::string p = hypre_matrix_problem(A); !p.empty()) return p;
  const int nf = amg_.options().num_functions;
  if (A.rows() % nf != 0) return fmt::format("{} unknowns are not {} per node", A.rows(), nf);
  if (amg_.options().interp_vec_variant > 0 && !mesh_view_.valid())
    return "rigid-body modes need set_mesh_view() (mesh and DOF map)";
  if (!mesh_view_.valid() || nf != 3) return {};
  // hypre assigns unknown i to function i % num_functions: the free DOFs must be
  // whole nodes in x, y, z order (DofMap constrains whole nodes, so they are).
  const std::vector<int>& free = mesh_view_.dofs->free_dofs();
  if (static_cast<Eigen::Index>(free.size()) != A.rows())
    return fmt::format("DOF map has {} free DOFs, matrix {} rows", free.size(), A.rows());
  for (size_t i = 0; i < free.size(); ++i)
    if (free[i] % 3 != static_cast<int>(i % 3) || free[i] / 3 != free[i - i % 3] / 3)
      return fmt::format("free DOF {} (global {}) breaks the node-interleaved x, y, z layout", i, free[i]);
  return {};
}

}  // namespace hofem
