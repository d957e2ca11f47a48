#pragma once
// A linear system assembled by several MPI ranks straight into hypre's IJ /
// ParCSR objects, solved by hypre's PCG or GMRES with BoomerAMG.
//
// The boundary with assembly is the serial one, on each rank's piece of the
// mesh: the rank assembles its own elements with the ordinary Assembler into a
// SparseMatrix over its local free DOFs (owned and ghost), and this class adds
// those values into the IJ matrix under the global row numbering
// (DistributedDofs). Contributions to rows another rank owns travel in
// HYPRE_IJMatrixAssemble. Right-hand sides and solutions are consistent local
// vectors (every ghost equal to its owner's value): the owned rows go into
// hypre's ParVector, and the solution's ghosts are filled from their owners.
// Newton, load stepping and time stepping thus run unchanged on local vectors.
#include "assembly/distributed_dofs.hpp"
#include "assembly/dof_map.hpp"
#include "linalg/sparse_matrix.hpp"
#include "mesh/mesh.hpp"
#include "linalg/linear_solver.hpp"
#include "solver/solver_spec.hpp"

#include <Eigen/Core>

#include <memory>
#include <string>

namespace hofem {

struct DistributedSolveResult {
  bool converged = false;
  int iterations = 0;
  double relative_residual = 0.0;  ///< hypre's final ||r|| / ||b||
  double solve_seconds = 0.0;      ///< Krylov iterations and the ghost update
  std::string message;
};

class DistributedLinearSystem {
 public:
  /// rows: the global numbering of this rank's local free DOFs (collective
  /// construction by distribute_dofs); kept by reference: it must outlive this.
  explicit DistributedLinearSystem(const DistributedDofs& rows, DistributedSolverOptions options = {});
  explicit DistributedLinearSystem(DistributedDofs&&, DistributedSolverOptions = {}) = delete;  // kept by reference
  ~DistributedLinearSystem();
  DistributedLinearSystem(const DistributedLinearSystem&) = delete;
  DistributedLinearSystem& operator=(const DistributedLinearSystem&) = delete;

  /// The rank's piece of the mesh and its DOF map (the one `rows` numbers), for
  /// the rigid-body modes; collective; ignored unless options.rigid_body_modes.
  void set_coordinates(const Mesh& local_mesh, const DofMap& dofs);
  /// Collective. Adds every rank's K_local (local free x local free) into the
  /// distributed matrix and sets BoomerAMG and the Krylov solver up for it.
  void assemble_matrix(const SparseMatrix& K_local);
  /// Collective. x = K^-1 b, b consistent over the local free DOFs (only owned
  /// rows are read); to ||r|| <= rtol ||b||; x: consistent.
  DistributedSolveResult solve(const Eigen::VectorXd& b, Eigen::VectorXd& x, double rtol = 1e-10,
                               int max_iterations = 1000);

  const DistributedDofs& rows() const { return rows_; }
  const DistributedSolverOptions& options() const { return options_; }
  /// Nonzeros this rank stores of the assembled matrix (its rows).
  long long local_nonzeros() const;
  /// Values this rank receives per matrix-vector product: the distinct
  /// off-rank columns of its rows (hypre's off-diagonal block). Bigger than the
  /// piece's ghost DOFs: an owned node on the interface also couples to nodes
  /// of the neighbour's elements that this rank's elements do not touch.
  long long matvec_receive_values() const;
  /// Time and counts over the object's life.
  struct Timings {
    int setups = 0, solves = 0;
    long long iterations = 0;
    double ij_seconds = 0.0;      ///< AddToValues + Assemble (the matrix's communication)
    double amg_seconds = 0.0;     ///< BoomerAMG set-up
    double krylov_seconds = 0.0;  ///< iterations (and the ghost update)
  };
  const Timings& timings() const { return timings_; }

 private:
  struct Hypre;
  const DistributedDofs& rows_;
  DistributedSolverOptions options_;
  Eigen::MatrixXd modes_;  ///< owned rows x 3 rigid rotations (empty without)
  std::unique_ptr<Hypre> hypre_;
  Timings timings_;
};

/// The LinearSolver face of a distributed system, for Newton and the problems
/// built on it: factorize() takes this rank's share of the matrix, solve() a
/// consistent right-hand side. Iterative: Newton's tolerances
/// (set_relative_tolerance) reach hypre's Krylov solver.
class DistributedHypreSolver final : public LinearSolver {
 public:
  explicit DistributedHypreSolver(const DistributedDofs& rows, DistributedSolverOptions options = {});
  std::string_view name() const override { return name_; }
  void analyze(const SparseMatrix&) override {}  // hypre has no separate symbolic phase: nothing to count
  bool factorize(const SparseMatrix& A) override;
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override;
  void set_relative_tolerance(double rtol) override { rtol_ = rtol; }
  bool is_iterative() const override { return true; }
  int last_iterations() const override { return last_.iterations; }
  std::string last_error() const override { return error_; }
  DistributedLinearSystem& system() { return system_; }
  const DistributedLinearSystem& system() const { return system_; }

 private:
  DistributedLinearSystem system_;
  std::string name_;
  double rtol_ = 1e-10;
  DistributedSolveResult last_;
  std::string error_;
};

}  // namespace hofem
