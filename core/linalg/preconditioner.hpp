#pragma once
// Preconditioners for the Krylov solvers (thesis §3.1): z = M^-1 r with M ~ A.
// Each is set up once per matrix (values) and applied every iteration; all are
// symmetric positive definite when A is SPD, which CG, CR and MINRES need.
#include "linalg/sparse_matrix.hpp"
#include "linalg/block_sparse_matrix.hpp"

#include <Eigen/Core>

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace hofem {

/// The mesh and DOF map of a system (assembly/mesh_view.hpp): linear algebra
/// passes it on to the mesh-aware preconditioners (solver/) and never looks inside.
struct MeshView;

/// The interface only: the algebraic preconditioners are in
/// linalg/algebraic_preconditioners.hpp and linalg/boomeramg.hpp, the
/// mesh-aware ones in solver/, and every name is in solver/solver_registry.cpp.
class Preconditioner {
 public:
  virtual ~Preconditioner() = default;
  /// The registry's name (solver/solver_registry.cpp; the factory sets it),
  /// empty for a preconditioner constructed directly.
  std::string_view name() const { return name_; }
  void set_name(std::string name) { name_ = std::move(name); }
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
  virtual void set_mesh_view(const MeshView&) {}
  const std::string& last_error() const { return error_; }

 protected:
  /// Records why setup() cannot build M and returns false: `return fail(why);`.
  bool fail(std::string why) {
    error_ = std::move(why);
    return false;
  }

  std::string error_;
  std::string name_;
};

}  // namespace hofem
