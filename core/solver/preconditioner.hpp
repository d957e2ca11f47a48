#pragma once
// Preconditioners for the Krylov solvers (thesis §3.1): z = M^-1 r with M ~ A.
// Each is set up once per matrix (values) and applied every iteration; all are
// symmetric positive definite when A is SPD, which CG, CR and MINRES need.
#include "assembly/sparse_matrix.hpp"
#include "solver/block_sparse_matrix.hpp"
#include "solver/mesh_view.hpp"

#include <Eigen/Core>

#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace hofem {

class Preconditioner {
 public:
  virtual ~Preconditioner() = default;
  virtual std::string_view name() const = 0;
  /// Builds M from A (A symmetric, stored in full). Returns false if it cannot
  /// (e.g. a non-positive diagonal for Jacobi), with the reason in last_error().
  virtual bool setup(const SparseMatrix& A) = 0;
  /// The same, given A's 3x3 block copy as well (the Krylov solver's operator),
  /// which a preconditioner working on blocks may use instead of converting A
  /// again; it must stay alive and unchanged while M is applied. Default: setup(A).
  virtual bool setup(const SparseMatrix& A, const BlockSparseMatrix<double>& blocks) {
    (void)blocks;
    return setup(A);
  }
  virtual void apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const = 0;
  /// Mesh and DOF map of the systems to come (before setup). Mesh-aware
  /// preconditioners need it and fail setup() without it; others ignore it.
  virtual void set_mesh_view(const MeshView& d) { mesh_view_ = d; }
  const std::string& last_error() const { return error_; }

 protected:
  /// Records why setup() cannot build M and returns false: `return fail(why);`.
  bool fail(std::string why) {
    error_ = std::move(why);
    return false;
  }

  std::string error_;
  MeshView mesh_view_;
};

/// "none", "jacobi", "block-jacobi" (3x3 nodal blocks), "ic0" (incomplete
/// Cholesky with zero fill, thesis Algorithm 2, diagonal shift retried on
/// breakdown: solver/incomplete_cholesky.hpp), "eigen-ict" (Eigen's
/// memory-limited incomplete Cholesky, Lin and More; natural ordering),
/// BoomerAMG variants "amg..." (solver/boomeramg.hpp), "pmg" (p-multigrid,
/// solver/p_multigrid.hpp), "schwarz" (element-block Additive Schwarz,
/// solver/additive_schwarz.hpp). Throws std::invalid_argument naming the valid choices.
std::unique_ptr<Preconditioner> make_preconditioner(std::string_view name);
std::vector<std::string> preconditioner_names();
/// True for preconditioners that need set_mesh_view() before setup().
bool preconditioner_needs_mesh_view(std::string_view name);

}  // namespace hofem
