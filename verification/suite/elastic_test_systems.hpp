#pragma once
// Small linear systems the solver tests and the solver checks share: a
// linear-elastic body clamped on its xmin face (the SPD matrices every solver
// and preconditioner must handle), a smooth right-hand side, and a
// preconditioner's M^-1 as a dense matrix for symmetry and definiteness checks.
#include "assembly/dof_map.hpp"
#include "linalg/sparse_matrix.hpp"
#include "mesh/box_mesh.hpp"
#include "mesh/mesh.hpp"
#include "assembly/mesh_view.hpp"
#include "linalg/preconditioner.hpp"

#include <Eigen/Core>

#include <string>

namespace hofem::verification {

/// Linear elasticity (E = 1, nu = 0.3) on a mesh clamped at its xmin face: the
/// stiffness over the free DOFs (SPD), with the mesh and DOF map that the
/// mesh-aware preconditioners (pmg, schwarz, amg with rigid-body modes) need.
struct ClampedElasticBody {
  Mesh mesh;
  DofMap dofs;
  SparseMatrix K;
  explicit ClampedElasticBody(Mesh m);
  /// The unit cube with n cells per side.
  ClampedElasticBody(CellType cell, int order, int n);
  ClampedElasticBody(const ClampedElasticBody&) = delete;  // mesh_view() points into it
  ClampedElasticBody& operator=(const ClampedElasticBody&) = delete;
  MeshView mesh_view() const { return {&mesh, &dofs}; }
  Eigen::Index unknowns() const { return K.rows(); }
};

/// b_i = sin(0.37 i) + 0.1: smooth, non-zero everywhere, not an eigenvector.
Eigen::VectorXd smooth_rhs(Eigen::Index n);

/// M^-1 as a dense n x n matrix, column i = M^-1 e_i.
Eigen::MatrixXd dense_inverse(const Preconditioner& M, Eigen::Index n);

/// Newton on a Neo-Hookean (E = 1, nu = 0.3) body clamped at xmin and pulled at
/// xmax by u = (0.1 x, 0.05 x y, 0), to |g| <= 1e-10 of the load, with the named
/// linear solver: what every solver must reproduce of CHOLMOD's solution (to
/// ~cond(K) 1e-10) when it drives the static solver.
struct PulledBodySolve {
  bool converged = false;
  std::string message;
  Eigen::VectorXd displacement;
};
PulledBodySolve solve_pulled_neohookean(const Mesh& mesh, const std::string& linear_solver);

}  // namespace hofem::verification
