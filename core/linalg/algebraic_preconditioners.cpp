#include "linalg/algebraic_preconditioners.hpp"

#include "linalg/incomplete_cholesky.hpp"


#include <Eigen/Dense>
#include <Eigen/IterativeLinearSolvers>
#include <fmt/format.h>

#include <memory>

namespace hofem {

namespace {

class IdentityPreconditioner final : public Preconditioner {
 public:
  bool setup(const SparseMatrix&) override { return true; }
  void apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const override { z = r; }
};

class JacobiPreconditioner final : public Preconditioner {
 public:
  bool setup(const SparseMatrix& A) override {
    inv_diag_ = A.diagonal();
    for (Eigen::Index i = 0; i < inv_diag_.size(); ++i) {
      if (!(inv_diag_[i] > 0.0))
        return fail(fmt::format("{}: diagonal entry {} is {} (needs > 0)", name(), i, inv_diag_[i]));
      inv_diag_[i] = 1.0 / inv_diag_[i];
    }
    return true;
  }
  void apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const override { z = inv_diag_.cwiseProduct(r); }

 private:
  Eigen::VectorXd inv_diag_;
};

// Inverse of each 3x3 diagonal block (the three displacement components of one
// node). The free-DOF numbering keeps a node's free components consecutive; a
// node with some components constrained simply has a smaller block, so blocks
// are taken as runs of 3 from the start and the tail is handled by Jacobi.
// Blocks are SPD when A is, so the preconditioner is SPD.
class BlockJacobiPreconditioner final : public Preconditioner {
 public:
  bool setup(const SparseMatrix& A) override {
    const Eigen::Index n = A.rows(), nb = n / 3;
    blocks_.assign(nb, Eigen::Matrix3d::Zero());
    for (Eigen::Index c = 0; c < 3 * nb; ++c)
      for (SparseMatrix::InnerIterator it(A, c); it; ++it)
        if (it.row() / 3 == c / 3) blocks_[c / 3](it.row() % 3, c % 3) = it.value();
    for (Eigen::Index b = 0; b < nb; ++b) {
      Eigen::LLT<Eigen::Matrix3d> llt(blocks_[b]);
      if (llt.info() != Eigen::Success)
        return fail(fmt::format("{}: diagonal block {} is not positive definite", name(), b));
      blocks_[b] = llt.solve(Eigen::Matrix3d::Identity());
    }
    tail_.resize(n - 3 * nb);
    for (Eigen::Index i = 3 * nb; i < n; ++i) tail_[i - 3 * nb] = 1.0 / A.coeff(i, i);
    return true;
  }
  void apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const override {
    z.resize(r.size());
    const Eigen::Index nb = static_cast<Eigen::Index>(blocks_.size());
    for (Eigen::Index b = 0; b < nb; ++b) z.segment<3>(3 * b) = blocks_[b] * r.segment<3>(3 * b);
    for (Eigen::Index i = 0; i < tail_.size(); ++i) z[3 * nb + i] = tail_[i] * r[3 * nb + i];
  }

 private:
  std::vector<Eigen::Matrix3d> blocks_;
  Eigen::VectorXd tail_;
};

// IC(0) of the thesis' Algorithm 2: zero fill on A's pattern
// (linalg/incomplete_cholesky.hpp, with its breakdown rule).
class IncompleteCholesky0Preconditioner final : public Preconditioner {
 public:
  bool setup(const SparseMatrix& A) override {
    return ic_.compute(A) || fail(std::string(name()) + ": a pivot stayed non-positive after 20 diagonal shifts");
  }
  void apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const override { ic_.solve(r, z); }

 private:
  IncompleteCholesky0 ic_;
};

// Eigen's IncompleteCholesky, under its own name: Lin and More's memory-limited
// incomplete Cholesky (the largest entries per column kept, with scaling and a
// growing shift on breakdown), not IC(0); until 2026-12 this was what "ic0"
// named, so earlier sweep results under "ic0" are this one. Natural ordering:
// Eigen's default AMD ordering gives ~2x more CG iterations on 3D elasticity
// (shared/machine.md).
class EigenIncompleteCholeskyPreconditioner final : public Preconditioner {
 public:
  bool setup(const SparseMatrix& A) override {
    ic_.compute(A);
    return ic_.info() == Eigen::Success || fail(std::string(name()) + ": factorisation failed");
  }
  void apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const override { z = ic_.solve(r); }

 private:
  Eigen::IncompleteCholesky<double, Eigen::Lower, Eigen::NaturalOrdering<std::int64_t>> ic_;
};

}  // namespace

std::unique_ptr<Preconditioner> make_identity_preconditioner() { return std::make_unique<IdentityPreconditioner>(); }
std::unique_ptr<Preconditioner> make_jacobi_preconditioner() { return std::make_unique<JacobiPreconditioner>(); }
std::unique_ptr<Preconditioner> make_block_jacobi_preconditioner() {
  return std::make_unique<BlockJacobiPreconditioner>();
}
std::unique_ptr<Preconditioner> make_ic0_preconditioner() {
  return std::make_unique<IncompleteCholesky0Preconditioner>();
}
std::unique_ptr<Preconditioner> make_eigen_ict_preconditioner() {
  return std::make_unique<EigenIncompleteCholeskyPreconditioner>();
}

}  // namespace hofem
