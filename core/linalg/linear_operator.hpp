#pragma once
// y = A x, whatever stores A: the Krylov methods (linalg/krylov.hpp) need only
// the product, so the same iteration runs on the assembled matrix or on its 3x3
// block copy (linalg/block_sparse_matrix.hpp), which moves half the bytes.
#include "linalg/sparse_matrix.hpp"
#include "linalg/block_sparse_matrix.hpp"

#include <Eigen/Core>

namespace hofem {

class LinearOperator {
 public:
  virtual ~LinearOperator() = default;
  virtual Eigen::Index rows() const = 0;
  /// y = A x (y resized).
  virtual void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const = 0;
};

/// The assembled matrix (Eigen's compressed-column product).
class SparseMatrixOperator final : public LinearOperator {
 public:
  explicit SparseMatrixOperator(const SparseMatrix& A) : A_(A) {}
  Eigen::Index rows() const override { return A_.rows(); }
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const override { y.noalias() = A_ * x; }

 private:
  const SparseMatrix& A_;
};

/// A 3x3 block matrix (parallel block rows).
template <class T>
class BlockOperator final : public LinearOperator {
 public:
  explicit BlockOperator(const BlockSparseMatrix<T>& A) : A_(A) {}
  Eigen::Index rows() const override { return A_.rows(); }
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const override { A_.multiply(x, y); }

 private:
  const BlockSparseMatrix<T>& A_;
};

}  // namespace hofem
