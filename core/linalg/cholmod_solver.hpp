#pragma once
// Sparse Cholesky through CHOLMOD's long-integer interface (cholmod_l_*): the
// int interface refuses factors with more than 2^31 entries, which P2/P3 meshes
// reach well below 10^6 unknowns. The symbolic analysis (fill-reducing ordering,
// supernodal structure) is done once per pattern and reused by every
// factorisation of every Newton iteration and time step; factorize() redoes it
// when the pattern changes (pattern_fingerprint).
#include "linalg/linear_solver.hpp"
#include "linalg/solver_method.hpp"

#include <cholmod.h>

namespace hofem {

class CholmodSolver final : public LinearSolver {
 public:
  /// serial_solves: factorise supernodally (BLAS, fast) as usual, but solve with
  /// a simplicial copy of the factor (no BLAS). For the small coarse levels of a
  /// multigrid, solved inside every preconditioner application: the supernodal
  /// solve's multithreaded BLAS calls there compete with the OpenMP threads of
  /// the rest of the cycle (measured on P3 n = 12, order-1 level of 6.6k
  /// unknowns: CG + pmg 85 ms per iteration with BLAS threads, 48 ms without; a
  /// simplicial factorisation instead would cost 0.09 s more per set-up).
  explicit CholmodSolver(bool serial_solves = false);
  ~CholmodSolver() override;
  CholmodSolver(const CholmodSolver&) = delete;
  CholmodSolver& operator=(const CholmodSolver&) = delete;

  std::string_view name() const override { return method_name(SolverMethod::Cholmod); }
  void analyze(const SparseMatrix& A) override;
  bool factorize(const SparseMatrix& A) override;
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override;

 private:
  cholmod_sparse view(const SparseMatrix& A) const;
  cholmod_common common_;
  cholmod_factor* factor_ = nullptr;
  cholmod_factor* solve_factor_ = nullptr;  // serial_solves: simplicial copy of factor_
  bool serial_solves_ = false;
  cholmod_dense *X_ = nullptr, *Y_ = nullptr, *E_ = nullptr;  // solve2 result and workspaces, reused
  std::uint64_t pattern_ = 0;  // pattern_fingerprint of the analysed matrix
  double factor_flops_ = 0.0, solve_flops_ = 0.0;  // of the analysed pattern: how many BLAS threads pay
};

}  // namespace hofem
