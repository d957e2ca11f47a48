#pragma once
// p-multigrid V-cycle preconditioner for element orders >= 2: thesis §3.1.3,
// Algorithm 3 with two levels — the mesh's own order-p space (level 2) and the
// order-1 space on the same mesh (level 1, solver/p_prolongation.hpp):
//
//   pre-smooth   z = S r                              (Alg. 3 line 3, from z = 0)
//   restrict     r_c = P^T (r - A z)                  (lines 4-5)
//   coarse solve z += P A_c^-1 r_c, A_c = P^T A P      (lines 7 and 9; CHOLMOD)
//   post-smooth  z += S^T (r - A z)                    (line 10)
//
// With S^T the adjoint of the pre-smoother and a convergent smoother the cycle is
// symmetric positive definite, so it preconditions CG, as in the p-multigrid
// preconditioners of deal.II (step-75: Chebyshev smoothing on the high order,
// order-1 coarse level) and MFEM (order-1 / low-order coarse space, Chebyshev
// smoothing, Galerkin or rediscretised coarse operator). Smoothers:
//  - Chebyshev (default): a degree-k Chebyshev polynomial in D^-1 A on
//    [lambda_max / range, lambda_max], D the 3x3 nodal blocks (or the diagonal),
//    lambda_max from a few Lanczos (CG) steps times a safety factor — deal.II's
//    PreconditionChebyshev. A polynomial in a symmetric operator is its own
//    adjoint; every step is a parallel (OpenMP) matrix-vector product.
//  - symmetric Gauss–Seidel (the thesis' GS_l): forward nodal-block sweeps before
//    the coarse correction, backward ones after. Serial.
//
// Order 1 has no coarser p level: setup() then fails with "pmg needs element
// order >= 2" (use amg or ic0 there). Without set_discretization() setup() fails.
// apply() allocates nothing of its own (mutable work vectors sized in setup(),
// so one instance must not be applied from two threads at once); the coarse
// CHOLMOD solve returns its result in a vector CHOLMOD allocates.
#include "solver/linear_solver.hpp"
#include "solver/p_prolongation.hpp"
#include "solver/preconditioner.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <memory>
#include <vector>

namespace hofem {

/// Defaults chosen by the measurements recorded in p_multigrid.cpp.
struct PMultigridOptions {
  enum class Smoother { Chebyshev, SymmetricGaussSeidel };
  Smoother smoother = Smoother::Chebyshev;
  bool block_scaling = true;       ///< 3x3 nodal blocks (else the diagonal) in both smoothers
  int chebyshev_degree = 3;        ///< matrix-vector products per smoothing
  double smoothing_range = 20.0;   ///< Chebyshev interval [lambda_max / range, lambda_max]
  int eigenvalue_iterations = 12;  ///< Lanczos (CG) steps estimating lambda_max(D^-1 A)
  double eigenvalue_safety = 1.2;  ///< the estimate is from below; scaled up by this
  int gauss_seidel_sweeps = 1;     ///< per pre- and per post-smoothing
};

class PMultigridPreconditioner final : public Preconditioner {
 public:
  explicit PMultigridPreconditioner(PMultigridOptions options = {});
  std::string_view name() const override { return "pmg"; }
  bool setup(const SparseMatrix& A) override;
  void apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const override;

  const PMultigridOptions& options() const { return options_; }
  Eigen::Index coarse_size() const { return transfer_.P.cols(); }
  const PProlongation& transfer() const { return transfer_; }
  /// Upper end of the Chebyshev interval (safety times the Lanczos estimate).
  double lambda_max() const { return lambda_max_; }
  /// Symbolic analyses of the coarse operator (CHOLMOD) so far: one per pattern.
  int coarse_analyses() const { return coarse_->analyses(); }

 private:
  bool prepare_levels(const SparseMatrix& A);
  bool build_scaling(const SparseMatrix& A);
  void estimate_lambda_max(const SparseMatrix& A);
  void scale(const double* in, double* out, Eigen::Index b) const;  // out_b = D_b^-1 in_b
  double row_dot(Eigen::Index i, const double* x) const;            // (A x)_i
  void residual(const Eigen::VectorXd& r, const Eigen::VectorXd& z, Eigen::VectorXd& res) const;
  void chebyshev(Eigen::VectorXd& z, bool final_residual) const;
  void gauss_seidel(const Eigen::VectorXd& r, Eigen::VectorXd& z, bool forward) const;

  PMultigridOptions options_;
  const SparseMatrix* A_ = nullptr;
  // Built once per discretization (Mesh and DofMap, by address) / pattern, reused by every setup.
  const Mesh* mesh_for_ = nullptr;
  const DofMap* dofs_for_ = nullptr;
  std::uint64_t pattern_hash_ = 0;  // pattern_fingerprint(A) the Galerkin product was analysed for
  PProlongation transfer_;
  GalerkinProduct galerkin_;
  std::vector<Eigen::Index> block_start_;  ///< nodal (or single-DOF) blocks of the free numbering
  // Values, rebuilt by every setup.
  SparseMatrix Ac_;
  std::unique_ptr<LinearSolver> coarse_;
  std::vector<Eigen::Matrix3d> block_inverse_;
  double lambda_max_ = 0.0;
  bool parallel_ = false;  ///< OpenMP loops in apply() (large enough matrices)
  // Work vectors of apply().
  mutable Eigen::VectorXd res_, d_, d_next_, rc_, xc_;
};

/// "pmg" with the default options.
std::unique_ptr<Preconditioner> make_p_multigrid_preconditioner();
std::unique_ptr<Preconditioner> make_p_multigrid_preconditioner(const PMultigridOptions& options);

}  // namespace hofem
