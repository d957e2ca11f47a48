#pragma once
// Sparse Cholesky through CHOLMOD's long-integer interface (cholmod_l_*): the
// int interface refuses factors with more than 2^31 entries, which P2/P3 meshes
// reach well below 10^6 unknowns. The symbolic analysis (fill-reducing ordering,
// supernodal structure) is done once per pattern and reused by every
// factorisation of every Newton iteration and time step; factorize() redoes it
// when the pattern changes (pattern_fingerprint).
#include "solver/linear_solver.hpp"

#include <cholmod.h>

namespace hofem {

class CholmodSolver final : public LinearSolver {
 public:
  CholmodSolver();
  ~CholmodSolver() override;
  CholmodSolver(const CholmodSolver&) = delete;
  CholmodSolver& operator=(const CholmodSolver&) = delete;

  std::string_view name() const override { return "cholmod"; }
  void analyze(const SparseMatrix& A) override;
  bool factorize(const SparseMatrix& A) override;
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override;

  /// Entries of the last factor (reported by benchmarks).
  double factor_nonzeros() const;

 private:
  cholmod_sparse view(const SparseMatrix& A) const;
  cholmod_common common_;
  cholmod_factor* factor_ = nullptr;
  cholmod_dense *X_ = nullptr, *Y_ = nullptr, *E_ = nullptr;  // solve2 result and workspaces, reused
  std::uint64_t pattern_ = 0;  // pattern_fingerprint of the analysed matrix
};

}  // namespace hofem
