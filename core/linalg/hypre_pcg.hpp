#pragma once
// hypre's own PCG (HYPRE_ParCSRPCG*) preconditioned with BoomerAMG, for
// comparison with our CG + "amg" (linalg/krylov.hpp) and as the solver of the
// distributed path to come. Same contract as KrylovSolver: stops when the
// relative residual ||b - A x|| / ||b|| reaches the tolerance (checked on the true
// residual after hypre stops), throws std::runtime_error if it does not converge.
#include "linalg/linear_solver.hpp"

#include <memory>
#include <string>

namespace hofem {

class BoomerAmgPreconditioner;

struct HyprePcgResult {
  bool converged = false;
  int iterations = 0;                 ///< summed over restarts
  double relative_residual = 0.0;     ///< true ||b - A x|| / ||b||
};

class HyprePcgSolver final : public LinearSolver {
 public:
  /// amg: the BoomerAMG preconditioner it owns (a variant of
  /// linalg/boomeramg_variants.hpp; the mesh-aware one of solver/ where the
  /// DOF layout is known).
  explicit HyprePcgSolver(std::unique_ptr<BoomerAmgPreconditioner> amg);
  ~HyprePcgSolver() override;
  std::string_view name() const override { return name_; }
  void analyze(const SparseMatrix& A) override;
  /// Converts A and sets BoomerAMG up; false (reason in last_error()) if A has
  /// non-finite entries, a non-positive diagonal or hypre fails.
  bool factorize(const SparseMatrix& A) override;
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override;
  void set_mesh_view(const MeshView& d) override;
  void set_relative_tolerance(double rtol) override { rtol_ = rtol; }
  bool is_iterative() const override { return true; }
  int last_iterations() const override { return last_.iterations; }
  const HyprePcgResult& last_result() const { return last_; }
  std::string last_error() const override { return error_; }

 private:
  struct Impl;  // hypre objects, kept out of this header
  std::unique_ptr<Impl> impl_;
  double rtol_ = 1e-8;
  int max_iterations_ = 5000;  // as KrylovOptions
  HyprePcgResult last_;
  std::string error_;
  std::string name_;  ///< "hypre-pcg+" and the BoomerAMG variant's name
};

}  // namespace hofem
