#pragma once
// p-multigrid V-cycle preconditioner (thesis §3.1.3, Algorithm 3) over a hierarchy
// of element orders on one mesh: order p, then p - 1, ..., 1 (or p straight to 1,
// PMultigridOptions::coarsening), as deal.II's step-75 and MFEM's p-multigrid do.
// Per level l, from z = 0:
//
//   pre-smooth   z = S r                              (Alg. 3 line 3)
//   restrict     r_c = P^T (r - A z)                  (lines 4-5)
//   coarse       z_c = V-cycle on level l + 1          (line 7, recursively)
//   prolong      z += P z_c                            (line 9)
//   post-smooth  z += S^T (r - A z)                    (line 10)
//
// and the order-1 level is solved by CHOLMOD when tiny, by one BoomerAMG V-cycle
// otherwise (direct_coarse_limit), so set-up time and memory grow linearly with
// the mesh. Coarse operators are Galerkin products P^T A P (solver/block_galerkin),
// exact coarse discretisations of whatever matrix is given (a Newton Hessian too).
//
// Smoother: Chebyshev polynomial of degree k in D^-1 A on [lambda_max / range,
// lambda_max], D the 3x3 nodal diagonal blocks, lambda_max from a few Lanczos (CG)
// steps times a safety factor (deal.II's PreconditionChebyshev). A polynomial in a
// symmetric operator is its own adjoint, so the cycle is symmetric positive
// definite and preconditions CG. The levels' operators are 3x3 block matrices in
// single precision (linalg/block_sparse_matrix.hpp): a smoother need not be exact,
// and the products, which are the cycle's cost, move 3.6x fewer bytes than the
// assembled double matrix. Vectors and sums stay in double.
//
// Finite cells (the mesh view names block elements, MeshView::block_elements):
// the fine level's smoother takes the Additive-Schwarz blocks of Longva et al.
// 2020 §5.2 for those cut cells and the 3x3 nodal blocks elsewhere
// (AdditiveSchwarzOptions::nodal_uncovered) in place of D, the same Chebyshev
// polynomial in S A. A small cut cell's basis functions are nearly linearly
// dependent, a mode no nodal diagonal sees and the coarse level cannot
// represent; its block inverse treats it, as in de Prenter et al.'s
// Schwarz-smoothed multigrid for immersed methods. The nodal blocks and the
// coarse level treat the stiff material, which the seed's one-level Schwarz
// "only treats ill-conditioning due to small volume overlaps, not" does not.
// Coarser p levels (Tet20 -> Tet10) keep D: their Galerkin operators are not
// held as a sparse matrix to map blocks into. Measured (Hex20 FCM twisting
// cylinder, box [12, 12, 18], 29,004 unknowns, E = 5e6, nu = 0.48, 3 implicit
// Euler steps, 9 Newton solves, CG to 1e-8): CG iterations 1343 with D, 517
// with the blocks (cells under a volume fraction of 0.5); with the order-1
// level factorised instead of one AMG V-cycle, 1171 and 478 - the smoother,
// not the coarse level, is what cut cells need.
//
// Order 1 has no coarser p level: setup() then fails with "pmg needs element order
// >= 2" (use amg there). Without set_mesh_view() setup() fails. apply() uses
// work vectors of its own (one instance must not be applied from two threads).
#include "assembly/mesh_view.hpp"
#include "solver/additive_schwarz.hpp"
#include "solver/block_galerkin.hpp"
#include "linalg/block_sparse_matrix.hpp"
#include "linalg/linear_solver.hpp"
#include "solver/p_hierarchy.hpp"
#include "linalg/preconditioner.hpp"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace hofem {

/// Defaults chosen by the measurements recorded in p_multigrid.cpp.
struct PMultigridOptions {
  enum class Coarsening {
    ByOne,     ///< p, p - 1, ..., 1
    ToLinear,  ///< p, 1
  };
  Coarsening coarsening = Coarsening::ByOne;
  int chebyshev_degree = 3;        ///< matrix-vector products per smoothing
  double smoothing_range = 20.0;   ///< Chebyshev interval [lambda_max / range, lambda_max]
  int eigenvalue_iterations = 12;  ///< Lanczos (CG) steps estimating lambda_max(D^-1 A)
  double eigenvalue_safety = 1.2;  ///< the estimate is from below; scaled up by this
  /// The order-1 level is factorised (CHOLMOD) up to this many unknowns, above it
  /// preconditioned by one BoomerAMG V-cycle. Measured (BM_TimeToError medians,
  /// limit 30,000 vs 2,000): P2 n = 12 0.369 vs 0.296 s, n = 16 0.996 vs 0.839 s;
  /// P3 n = 8 0.424 vs 0.402 s, n = 12 1.76 vs 1.61 s, n = 16 4.41 vs 4.08 s; NH P3
  /// n = 8 1.35 vs 1.33 s. The factorisation's cost grows superlinearly (0.22 s
  /// for the 10k order-1 unknowns of P2 n = 16), AMG's set-up linearly, for one or
  /// two more CG iterations. (A process's first BoomerAMG set-up also starts MPI
  /// and hypre, ~0.15 s once.)
  Eigen::Index direct_coarse_limit = 2000;
  std::string coarse_amg = "amg";  ///< the BoomerAMG variant above the limit (linalg/boomeramg.hpp)
};

class PMultigridPreconditioner final : public Preconditioner {
 public:
  explicit PMultigridPreconditioner(PMultigridOptions options = {});
  ~PMultigridPreconditioner() override;
  bool setup(const SparseMatrix& A) override;
  /// Uses `blocks` (A's block copy, alive while applied) as the fine level's operator.
  bool setup(const SparseMatrix& A, const BlockSparseMatrix<double>& blocks) override;
  void apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const override;
  void set_mesh_view(const MeshView& d) override { mesh_view_ = d; }

  /// Levels including the order-1 level (0 before the first setup).
  int num_levels() const { return hierarchy_ ? hierarchy_->num_levels() : 0; }
  /// True when the order-1 level is factorised, false when BoomerAMG handles it.
  bool direct_coarse() const { return direct_coarse_; }
  /// Cut-cell Schwarz blocks in the fine level's smoother (0: the nodal diagonal only).
  int smoother_blocks() const { return !levels_.empty() && levels_[0].blocks ? levels_[0].blocks->num_blocks() : 0; }
  /// Symbolic analyses of the order-1 operator by CHOLMOD so far (one per pattern).
  int coarse_analyses() const;
  /// Bytes one apply() moves at least (the formula in p_multigrid.cpp), for
  /// floor ratios: each smoothed level's single-precision products and vector
  /// passes, the transfers, the order-1 level as one pass over its matrix.
  double bytes_per_apply() const;

 private:
  MeshView mesh_view_;
  struct Level {
    BlockSparseMatrix<double> exact;   ///< the level's operator (Galerkin source of the next level)
    BlockSparseMatrix<float> smooth;   ///< the same in single precision, for smoothing and residuals
    std::vector<Eigen::Matrix3d> inverse_diagonal;  ///< D_b^-1 per node
    /// Finite cells, fine level: the cut cells' Schwarz blocks replace D (null: D).
    std::unique_ptr<AdditiveSchwarzPreconditioner> blocks;
    double lambda_max = 0.0;
    mutable Eigen::VectorXd res, d, d_next, b_coarse, x_coarse, w;  ///< work vectors of apply()
  };
  bool check(const SparseMatrix& A);
  bool prepare(const SparseMatrix& A, const BlockSparseMatrix<double>* blocks);
  bool set_level_values(Level& level, std::size_t index);
  /// Level l's operator: the caller's block copy for the fine level when given.
  const BlockSparseMatrix<double>& level_operator(std::size_t l) const {
    return l == 0 && fine_blocks_ ? *fine_blocks_ : levels_[l].exact;
  }
  /// The operator of the level below l: level l + 1's, or the order-1 level's.
  BlockSparseMatrix<double>& coarser_operator(std::size_t l) {
    return l + 1 < levels_.size() ? levels_[l + 1].exact : coarse_;
  }
  void estimate_lambda_max(Level& level) const;
  void chebyshev(const Level& level, Eigen::VectorXd& z, bool final_residual) const;
  /// The same with the level's Schwarz blocks in place of D (unfused: S is global).
  void chebyshev_blocks(const Level& level, Eigen::VectorXd& z, bool final_residual) const;
  /// z = S r: the level's blocks, or D^-1.
  void smoother_inverse(const Level& level, const Eigen::VectorXd& r, Eigen::VectorXd& z) const;
  void vcycle(std::size_t l, const Eigen::VectorXd& b, Eigen::VectorXd& x) const;

  PMultigridOptions options_;
  // Built once per mesh view and fine pattern. The mesh view is known
  // by its DOF map's identity (DofMap::identity: new for every map built, where
  // an address is reused) and the shape of its mesh, which a DOF map is built for.
  std::uint64_t dofs_identity_ = 0;
  std::array<std::int64_t, 4> mesh_shape_{};  ///< cell, order, nodes, elements
  std::uint64_t pattern_hash_ = 0;
  const BlockSparseMatrix<double>* fine_blocks_ = nullptr;  ///< setup(A, blocks)'s blocks
  std::unique_ptr<PHierarchy> hierarchy_;
  std::vector<Level> levels_;  ///< all but the order-1 level
  // The order-1 level.
  BlockSparseMatrix<double> coarse_;
  bool direct_coarse_ = true;
  std::unique_ptr<LinearSolver> coarse_direct_;
  std::unique_ptr<Preconditioner> coarse_amg_;
};

}  // namespace hofem
