#pragma once
// Element-block Additive-Schwarz preconditioner of Longva et al. 2020
// (§5.2, eq. 13-14), after de Prenter et al. 2017/2019:
//
//   S = sum_K R_K^T C_K^+ R_K,   C_K = R_K C R_K^T                      (eq. 13)
//
// where R_K selects the free DOFs of element K and C_K is the submatrix of the
// GLOBAL matrix on those DOFs (it already holds the neighbours' contributions,
// unlike the element matrix). C_K^+ is the "reflected pseudo-inverse" of eq. 14:
// with C_K = V diag(lambda) V^T,
//
//   lambda_k(S_K) = 1 / |lambda_k|        if |lambda_k| >= eps lambda_max,
//                   eps / lambda_max      otherwise,                     (eq. 14)
//
// (lambda_max: the eigenvalue of largest magnitude; eps ~ 1e-13). Small
// eigenvalues get a tiny inverse, as in a truncated pseudo-inverse, but not
// zero, and negative ones are reflected, so S is symmetric positive definite
// even when C is indefinite (MINRES needs an SPD preconditioner). Only the selected elements contribute blocks (in the
// finite cell method: cut cells under a volume-fraction threshold); DOFs in no
// selected block are preconditioned by the diagonal, 1 / |C_ii| (eq. 14 for a
// 1 x 1 block).
//
// Caches and when they are rebuilt:
//  - block index lists R_K and, per DOF, where its block entries lie: once per
//    set_mesh_view() (on the next setup());
//  - the map from each block entry to its position in A's value array: when
//    A's size or number of nonzeros changes, or an entry is found moved;
//  - S_K (dense, symmetric): every setup().
#include "assembly/mesh_view.hpp"
#include "linalg/preconditioner.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <span>
#include <vector>

namespace hofem {

struct AdditiveSchwarzOptions {
  /// Elements contributing a block (ids into mesh.elements); empty = those the
  /// mesh view names (MeshView::block_elements), or all if it names none.
  std::vector<int> elements;
  /// Relative eigenvalue threshold of eq. 14 (the paper's ~1e-13).
  double epsilon = 1e-13;
  /// Invert an SPD block with cond_2 < min(1e8, 1/epsilon) (Frobenius bound) by
  /// Cholesky: eq. 14 then changes no eigenvalue, so S_K is the same, 2.5-5x cheaper.
  /// Other blocks (indefinite, nearly singular) always take the eigen-decomposition.
  bool cholesky_fast_path = true;
  /// DOFs in no block, taken a node at a time (its three DOFs, free indices
  /// 3k, 3k + 1, 3k + 2): the inverse of their 3x3 diagonal block instead of
  /// 1 / |A_ii|. The p-multigrid's smoother on finite cells uses this: the cut
  /// cells' blocks where the volume fraction is small, the nodal blocks that
  /// smooth elasticity best (p_multigrid.hpp) everywhere else.
  bool nodal_uncovered = false;
};

class AdditiveSchwarzPreconditioner final : public Preconditioner {
 public:
  explicit AdditiveSchwarzPreconditioner(AdditiveSchwarzOptions options = {}) : options_(std::move(options)) {}

  void set_mesh_view(const MeshView& d) override;
  /// Fails (with last_error()) without a mesh view, on a size mismatch, an
  /// element id out of range, a non-finite entry in A, a zero block or a zero
  /// diagonal entry of an uncovered DOF.
  bool setup(const SparseMatrix& A) override;
  /// z = sum_K R_K^T S_K R_K r + D^-1 r on uncovered DOFs. Deterministic (the
  /// same bits for any thread count) and allocation-free once z has r's size.
  /// Uses workspace owned by this object: one apply() at a time per object.
  void apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const override;

  int num_blocks() const { return static_cast<int>(block_element_.size()); }
  /// Free DOFs of block b (the rows/columns of R_K).
  std::span<const int> block_dofs(int b) const;
  /// S_K = C_K^+ of block b after setup() (dense, column-major, symmetric).
  Eigen::Map<const Eigen::MatrixXd> block_inverse(int b) const;
  /// Free DOFs in no selected block (Jacobi-preconditioned).
  int num_uncovered() const { return static_cast<int>(uncovered_.size()); }
  /// Eigenvalues of all blocks replaced by eps / lambda_max at the last setup().
  std::int64_t num_truncated() const { return num_truncated_; }
  /// Negative eigenvalues above the threshold, replaced by 1 / |lambda|.
  std::int64_t num_reflected() const { return num_reflected_; }

 private:
  MeshView mesh_view_;
  bool build_blocks();
  void build_entry_map(const SparseMatrix& A);
  bool entry_map_matches(const SparseMatrix& A) const;

  AdditiveSchwarzOptions options_;
  bool blocks_built_ = false;
  bool ready_ = false;  ///< last setup() succeeded

  // Block b's DOFs are dofs_[dof_ptr_[b] .. dof_ptr_[b+1]) (slots of block b).
  std::vector<int> block_element_;
  std::vector<std::int64_t> dof_ptr_;
  std::vector<int> dofs_;
  // Slots holding free DOF i: slots_[slot_ptr_[i] .. slot_ptr_[i+1]), ascending.
  std::vector<std::int64_t> slot_ptr_, slots_;
  std::vector<int> uncovered_;  ///< free DOFs in no block

  // Lower triangle of every C_K, column by column: position in A's value array
  // (-1 where A stores no entry, i.e. a structural zero).
  std::vector<std::int64_t> entry_ptr_;
  std::vector<std::int64_t> entry_;
  Eigen::Index map_rows_ = -1, map_nonzeros_ = -1;

  std::vector<std::int64_t> value_ptr_;  ///< per block, start of S_K in values_
  std::vector<double> values_;
  Eigen::VectorXd jacobi_;  ///< 1/|A_ii| on uncovered DOFs, 0 on covered ones (not nodal_uncovered)
  std::vector<int> uncovered_nodes_;                 ///< nodal_uncovered: k for DOFs 3k..3k+2
  std::vector<Eigen::Matrix3d> uncovered_inverse_;   ///< their 3x3 diagonal blocks' inverses
  std::int64_t num_truncated_ = 0, num_reflected_ = 0;

  // apply() workspace, one entry per slot: R_K r and S_K R_K r of every block.
  mutable Eigen::VectorXd gathered_, product_;
};

}  // namespace hofem
