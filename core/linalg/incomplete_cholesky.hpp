#pragma once
// Incomplete Cholesky with zero fill, IC(0) (thesis Algorithm 2; Saad, Iterative
// Methods for Sparse Linear Systems, §10.3.2): L L^T ~= A with L on exactly the
// pattern of A's lower triangle, and (L L^T)(i, j) = A(i, j) wherever A has an
// entry (the fill that a complete factor would create is dropped).
//
// Breakdown rule: a pivot d_k = A(k, k) - sum_j L(k, j)^2 <= 0 (IC(0) of an SPD
// matrix exists for M-matrices, not in general: elasticity is not one) restarts
// the factorisation of A + alpha diag(A) with alpha = 1e-3, doubled at each
// restart up to 20 restarts (Manteuffel's shift, as PETSc and Eigen use);
// shift() reports the alpha used (0: none needed).
#include "linalg/sparse_matrix.hpp"

#include <Eigen/Core>

namespace hofem {

class IncompleteCholesky0 {
 public:
  /// Factorises the symmetric A (stored in full or lower, compressed columns).
  /// False if no shift up to the last restart gave positive pivots.
  bool compute(const SparseMatrix& A);
  /// z = (L L^T)^{-1} r.
  void solve(const Eigen::VectorXd& r, Eigen::VectorXd& z) const;
  /// The factor (lower triangular, compressed columns, diagonal first in each column).
  const SparseMatrix& lower() const { return L_; }
  double shift() const { return shift_; }

 private:
  bool factorize(const SparseMatrix& lower_a, double alpha);
  SparseMatrix L_;
  double shift_ = 0.0;
};

}  // namespace hofem
