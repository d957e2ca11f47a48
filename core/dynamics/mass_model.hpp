#pragma once
// The mass of a body in motion: lumped (a diagonal, row sums or HRZ) or
// consistent (one scalar matrix over all nodes: its free block enters the
// implicit systems, the rest kinetic energy and prescribed accelerations), built
// once from the discretization, and for explicit integrators with the consistent
// mass the CHOLMOD factor of its free block, made again when the DOF map changes
// (a released node set).
// Distributed: every vector and matrix is this rank's elements' share.
#include "linalg/sparse_matrix.hpp"
#include "problem/discretization.hpp"
#include "linalg/linear_solver.hpp"

#include <Eigen/Core>

#include <memory>
#include <string>

namespace hofem {

enum class MassKind { Consistent, Lumped };

class MassModel {
 public:
  /// `degree`: the quadrature degree of N_i N_j (2p on affine cells); `factorize`:
  /// keep a CHOLMOD factor of the free consistent mass (explicit integrators).
  /// Throws std::invalid_argument for a lumping with a non-positive nodal mass.
  MassModel(const Discretization& disc, double density, MassKind kind, MassLumping lumping, int degree,
            int quadrature_degree, bool factorize);
  MassModel(Discretization&&, double, MassKind, MassLumping, int, int, bool) = delete;  // kept by reference

  bool lumped() const { return kind_ == MassKind::Lumped; }
  int degree() const { return degree_; }
  /// "lumped (row-sum)", "lumped (HRZ)" or "consistent".
  std::string name() const;
  /// Lumped: the mass per DOF, all DOFs.
  const Eigen::VectorXd& diagonal() const { return lumped_; }
  /// Consistent: M_ff w over the free DOFs.
  Eigen::VectorXd free_times(const Eigen::VectorXd& w) const;
  /// Consistent: K += s M_ff for K with the free-DOF pattern of the
  /// discretization's assembler (every element node pair is in it).
  void add_free_to(SparseMatrix& K, double s) const;
  /// M r over all DOFs.
  Eigen::VectorXd times(const Eigen::VectorXd& r) const;
  Eigen::VectorXd consistent_times(const Eigen::VectorXd& r) const;
  /// x = M_ff^-1 b with the factor (made with `factorize`).
  void solve_free(const Eigen::VectorXd& b, Eigen::VectorXd& x) const { solver_->solve(b, x); }
  /// The smallest diagonal entry over the free DOFs (lumped: nodal mass; consistent: of M_ff).
  double min_diagonal() const;
  /// After the discretization's DOF map changed: the factor of M_ff anew.
  void rebuild();

  int matrices_built() const { return matrices_built_; }  ///< sparse consistent mass matrices
  int factorizations() const { return factorizations_; }

 private:
  void factorize_free();
  const Discretization& disc_;
  double density_;
  MassKind kind_;
  MassLumping lumping_;
  int degree_, quadrature_degree_;
  Eigen::VectorXd lumped_;
  /// Consistent, over all nodes: M = Ms (x) I3. One scalar matrix serves the
  /// free block (Newton's matrix and products), the prescribed coupling and the
  /// kinetic energy: at Tet10 it is ~1/20 of the two DOF matrices it replaced.
  NodalMatrix Ms_;
  std::unique_ptr<LinearSolver> solver_;
  mutable int matrices_built_ = 0;
  int factorizations_ = 0;
};

}  // namespace hofem
