#pragma once
// A linear system assembled by several MPI ranks straight into hypre's IJ /
// ParCSR objects (issue 7), solved by hypre's PCG with BoomerAMG.
//
// The boundary with assembly stays the serial one: each rank assembles its own
// elements with the ordinary Assembler into a SparseMatrix over the serial free
// numbering (the elements of other parts contribute nothing: ElementRules with
// empty rules, see assembly/element_rules), and this class adds those values
// into the IJ matrix under the distributed row numbering (DistributedDofs).
// Contributions to rows another rank owns (the ghost rows) travel in
// HYPRE_IJMatrixAssemble. The solution comes back on every rank in the serial
// free numbering, so Newton, load stepping and time stepping run unchanged.
//
// What is still serial (and what a larger run would change first): every rank
// holds the whole mesh, the full sparsity pattern and full-length vectors; the
// solution is all-gathered after each solve. The IJ matrix, BoomerAMG's
// hierarchy and the Krylov iterations are distributed.
#include "assembly/distributed_dofs.hpp"
#include "assembly/dof_map.hpp"
#include "assembly/sparse_matrix.hpp"
#include "solver/linear_solver.hpp"

#include <Eigen/Core>
#include <mpi.h>

#include <memory>
#include <string>

namespace hofem {

struct DistributedSolveResult {
  bool converged = false;
  int iterations = 0;
  double relative_residual = 0.0;  ///< hypre's final ||r|| / ||b||
  double setup_seconds = 0.0;      ///< IJ assembly (with its communication) and BoomerAMG set-up
  double solve_seconds = 0.0;      ///< PCG iterations and the all-gather
  std::string message;
};

class DistributedLinearSystem {
 public:
  /// rows: the numbering of `dofs`' free DOFs over the ranks of comm (parts = comm size).
  DistributedLinearSystem(MPI_Comm comm, DistributedDofs rows, const DofMap& dofs);
  ~DistributedLinearSystem();
  DistributedLinearSystem(const DistributedLinearSystem&) = delete;
  DistributedLinearSystem& operator=(const DistributedLinearSystem&) = delete;

  /// Collective. Sums every rank's K_local (num_free x num_free, serial free
  /// numbering) into the distributed matrix and sets BoomerAMG and PCG up for it.
  /// Returns the set-up seconds.
  double assemble_matrix(const SparseMatrix& K_local);
  /// Collective. x = K^-1 b for a right-hand side every rank holds in full
  /// (serial free numbering); PCG + BoomerAMG (3 functions per node) to
  /// ||r|| <= rtol ||b||; x: the full solution, on every rank.
  DistributedSolveResult solve(const Eigen::VectorXd& b, Eigen::VectorXd& x, double rtol = 1e-10,
                               int max_iterations = 1000);
  /// Both, for a right-hand side of which each rank holds its own elements' share.
  DistributedSolveResult assemble_and_solve(const SparseMatrix& K_local, const Eigen::VectorXd& b_local,
                                            Eigen::VectorXd& x, double rtol = 1e-10);

  const DistributedDofs& rows() const { return rows_; }
  int rank() const { return rank_; }
  int size() const { return size_; }
  /// Nonzeros this rank stores of the assembled matrix (its rows).
  long long local_nonzeros() const;

 private:
  struct Hypre;
  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
  DistributedDofs rows_;
  std::vector<int> row_of_free_;  ///< free index -> global row
  std::unique_ptr<Hypre> hypre_;
};

/// The LinearSolver face of a distributed system, for Newton and the problems
/// built on it: factorize() takes this rank's share of the matrix, solve() a
/// right-hand side every rank holds in full (a gradient summed over ranks).
/// Iterative: Newton's tolerances (set_relative_tolerance) reach hypre's PCG.
class DistributedHypreSolver final : public LinearSolver {
 public:
  DistributedHypreSolver(MPI_Comm comm, DistributedDofs rows, const DofMap& dofs);
  std::string_view name() const override { return "distributed hypre-pcg+amg"; }
  void analyze(const SparseMatrix&) override {}  // hypre has no separate symbolic phase: nothing to count
  bool factorize(const SparseMatrix& A) override;
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override;
  void set_relative_tolerance(double rtol) override { rtol_ = rtol; }
  bool is_iterative() const override { return true; }
  int last_iterations() const override { return last_.iterations; }
  std::string last_error() const override { return error_; }
  const DistributedSolveResult& last() const { return last_; }
  const DistributedLinearSystem& system() const { return system_; }

 private:
  DistributedLinearSystem system_;
  double rtol_ = 1e-10;
  DistributedSolveResult last_;
  std::string error_;
};

}  // namespace hofem
