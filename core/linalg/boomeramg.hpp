#pragma once
// Algebraic multigrid preconditioner through hypre's BoomerAMG, configured for
// elasticity: systems AMG with three functions (x, y, z) per node, one V-cycle
// per application. Two levels:
//   - BoomerAmg works on hypre objects only (a ParCSR matrix, ParVectors), so the
//     MPI-distributed assembly can hand in its own ParCSR matrix; hypre's
//     PCG (linalg/hypre_pcg.hpp) uses it as its preconditioner too.
//   - BoomerAmgPreconditioner wraps it as a Preconditioner on our serial
//     SparseMatrix (converted by linalg/hypre_matrix.hpp).
// Parameter meanings: hypre 2.26, HYPRE_parcsr_ls.h (the BoomerAMG reference);
// the measurements behind the defaults are in boomeramg_variants.cpp.
#include "linalg/hypre_matrix.hpp"
#include "linalg/preconditioner.hpp"
#include "linalg/boomeramg_variants.hpp"

#include <HYPRE_parcsr_ls.h>
#include <Eigen/Core>

#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace hofem {

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
/// num_functions, or a row layout that is not node-interleaved; hypre errors are
/// reported the same way. It knows matrices only: what a mesh adds (which DOF
/// each row is, the rigid rotations for interp_vec_variant > 0) is handed in by
/// set_row_layout(), which the mesh-aware subclass in solver/ calls from
/// set_mesh_view().
class BoomerAmgPreconditioner : public Preconditioner {
 public:
  BoomerAmgPreconditioner(std::string name, const BoomerAmgOptions& options) : amg_(options) { set_name(std::move(name)); }
  /// row_dofs[i]: the global DOF (3 node + component) of row i, checked for the
  /// node-interleaved x, y, z layout hypre's systems AMG assumes; modes: the
  /// near-null-space vectors (rows x k) for interp_vec_variant > 0, else empty.
  void set_row_layout(std::vector<int> row_dofs, Eigen::MatrixXd modes);
  bool setup(const SparseMatrix& A) override;
  void apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const override;
  /// The converted matrix and the set-up hierarchy (for hypre's PCG).
  const HypreMatrix& matrix() const { return A_; }
  const BoomerAmg& amg() const { return amg_; }

 private:
  std::string check(const SparseMatrix& A) const;

  HypreMatrix A_;
  // apply() is const in the interface, but hypre's solve writes into its vectors.
  mutable HypreVector b_, x_;
  BoomerAmg amg_;  // after A_, b_, x_: destroyed before the objects it refers to
  Eigen::Index rows_ = 0;
  bool ready_ = false;
  bool has_layout_ = false;
  std::vector<int> row_dofs_;
  Eigen::MatrixXd modes_;
};

}  // namespace hofem
