#pragma once
// Algebraic multigrid preconditioner through hypre's BoomerAMG, configured for
// elasticity: systems AMG with three functions (x, y, z) per node, one V-cycle
// per application. Two levels:
//   - BoomerAmg works on hypre objects only (a ParCSR matrix, ParVectors), so the
//     MPI-distributed assembly can hand in its own ParCSR matrix; hypre's
//     PCG (solver/hypre_pcg.hpp) uses it as its preconditioner too.
//   - BoomerAmgPreconditioner wraps it as a Preconditioner on our serial
//     SparseMatrix (converted by solver/hypre_matrix.hpp).
// Parameter meanings: hypre 2.26, HYPRE_parcsr_ls.h (the BoomerAMG reference);
// the measurements behind the defaults are in boomeramg.cpp.
#include "solver/hypre_matrix.hpp"
#include "solver/preconditioner.hpp"
#include "solver/solver_spec.hpp"  // boomeramg_variant_names

#include <HYPRE_parcsr_ls.h>
#include <Eigen/Core>

#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace hofem {

/// BoomerAMG parameters, each passed to the matching HYPRE_BoomerAMGSet* call
/// (relax_*: SetCycleRelaxType); values as documented in HYPRE_parcsr_ls.h.
struct BoomerAmgOptions {
  int num_functions = 3;          ///< unknowns per node, interleaved (x0 y0 z0 x1 ...)
  int coarsen_type = 10;          ///< 10: HMIS
  int interp_type = 6;            ///< 6: extended+i
  int p_max_elmts = 4;            ///< interpolation truncated to this many entries per row
  double strong_threshold = 0.5;  ///< strength of connection
  int relax_down = 13;            ///< smoother before coarse correction (13: l1 Gauss-Seidel forward)
  int relax_up = 14;              ///< and after (14: the backward sweep, its adjoint)
  int relax_coarse = 9;           ///< 9: Gaussian elimination on the coarsest level
  int num_sweeps = 1;
  int nodal = 0;                  ///< >0: nodal coarsening with this block norm (1: Frobenius, 4: row sum)
  int agg_num_levels = 0;         ///< levels of aggressive coarsening
  int agg_interp_type = 4;        ///< interpolation on those levels (4: multipass)
  int agg_p_max_elmts = 0;
  int num_paths = 1;
  /// >0: rigid-body rotations added to interpolation (InterpVecVariant; needs
  /// nodal coarsening and the node coordinates, i.e. set_mesh_view()).
  int interp_vec_variant = 0;
  int interp_vec_q_max = 4;
};

/// Options of a variant name; throws std::invalid_argument for an unknown one.
BoomerAmgOptions boomeramg_options(std::string_view variant);

/// BoomerAMG on hypre objects, as a preconditioner: tolerance 0, one V-cycle per
/// apply from a zero initial guess, no printing. Not thread-safe.
class BoomerAmg {
 public:
  explicit BoomerAmg(const BoomerAmgOptions& options) : options_(options) {}
  ~BoomerAmg() { reset(); }
  BoomerAmg(const BoomerAmg&) = delete;
  BoomerAmg& operator=(const BoomerAmg&) = delete;

  /// Builds the hierarchy for A on a freshly configured solver (a previous one is
  /// destroyed); b, x: vectors laid out like A's rows (hypre's set-up interface
  /// takes them). modes: near-null-space vectors for interp_vec_variant > 0, the
  /// locally owned rows of each column (rigid rotations for elasticity).
  /// Throws std::runtime_error if hypre reports an error.
  void setup(HYPRE_ParCSRMatrix A, HYPRE_ParVector b, HYPRE_ParVector x, const Eigen::MatrixXd* modes = nullptr);
  /// x = M^-1 b: one V-cycle from x = 0.
  void apply(HYPRE_ParCSRMatrix A, HYPRE_ParVector b, HYPRE_ParVector x) const;
  /// The set-up hypre solver (for HYPRE_ParCSRPCGSetPrecond), or nullptr.
  HYPRE_Solver handle() const { return solver_; }
  /// The set-up function to pass with handle(): setup() built the hierarchy
  /// already, so the Krylov solver's set-up, which calls this, has nothing left to do.
  static HYPRE_Int already_set_up(HYPRE_Solver, HYPRE_ParCSRMatrix, HYPRE_ParVector, HYPRE_ParVector) { return 0; }
  const BoomerAmgOptions& options() const { return options_; }
  /// Frees the hierarchy. It refers to the matrix and vectors of the last
  /// set-up: call this before they go.
  void reset();

 private:

  BoomerAmgOptions options_;
  HYPRE_Solver solver_ = nullptr;
  // hypre keeps pointers to the level-0 interpolation vectors and their array
  // (and does not free them): they live as long as the solver.
  std::vector<std::unique_ptr<HypreVector>> modes_;
  std::vector<HYPRE_ParVector> mode_handles_;
};

/// The "amg..." preconditioners: BoomerAmg on our serial SparseMatrix, converted
/// to a ParCSR matrix whose structure is reused while the pattern stays the same.
/// setup() refuses (false, reason in last_error()) matrices with non-finite
/// entries, a non-positive diagonal, a row count that is not a multiple of
/// num_functions, or a DOF map that is not node-interleaved; hypre errors are
/// reported the same way.
class BoomerAmgPreconditioner final : public Preconditioner {
 public:
  BoomerAmgPreconditioner(std::string name, const BoomerAmgOptions& options) : name_(std::move(name)), amg_(options) {}
  std::string_view name() const override { return name_; }
  bool setup(const SparseMatrix& A) override;
  void apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const override;
  /// The converted matrix and the set-up hierarchy (for hypre's PCG).
  const HypreMatrix& matrix() const { return A_; }
  const BoomerAmg& amg() const { return amg_; }

 private:
  std::string check(const SparseMatrix& A) const;

  std::string name_;
  HypreMatrix A_;
  // apply() is const in the interface, but hypre's solve writes into its vectors.
  mutable HypreVector b_, x_;
  BoomerAmg amg_;  // after A_, b_, x_: destroyed before the objects it refers to
  Eigen::Index rows_ = 0;
  bool ready_ = false;
};

/// The rigid rotations (e_k x (X - centre), k = x, y, z) of the free DOFs of d:
/// num_free x 3; centre: the nodes' centroid unless given (a distributed system
/// passes one centre to every rank, so that the ranks' rows form global modes).
/// Translations need no vectors: systems AMG interpolates each displacement
/// component separately and keeps constants.
Eigen::MatrixXd rigid_rotations(const MeshView& d, const Eigen::Vector3d* centre = nullptr);

}  // namespace hofem
