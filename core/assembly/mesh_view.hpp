#pragma once
// What a mesh-aware preconditioner may know about the system besides its matrix:
// the mesh (elements, vertices, order) and the map from global DOFs to the free
// numbering of the matrix. Purely algebraic preconditioners ignore it; the
// p-multigrid (needs the order-1 space of the same mesh) and the element-block
// Additive-Schwarz preconditioner (needs each element's DOFs) require it.
#include "assembly/dof_map.hpp"
#include "mesh/mesh.hpp"

#include <Eigen/Core>

#include <vector>

namespace hofem {

/// The mesh and DOF map of a system, as a preconditioner sees them (not
/// owned). Discretization (problem/discretization.hpp) is what owns them.
/// Linear algebra (linalg/) knows it by name only: its LinearSolver and
/// Preconditioner interfaces pass it on to the mesh-aware preconditioners of
/// solver/ and never look inside.
struct MeshView {
  const Mesh* mesh = nullptr;
  const DofMap* dofs = nullptr;
  /// Elements that need a block of their own in block preconditioners (the
  /// finite cell method's cut cells under a volume-fraction threshold, Longva
  /// et al. 2020 §5.2); null: every element. Non-null and empty: none (diagonal only).
  const std::vector<int>* block_elements = nullptr;
  bool valid() const { return mesh != nullptr && dofs != nullptr; }
};

/// The rigid rotations (e_k x (X - centre), k = x, y, z) of the free DOFs of d:
/// num_free x 3; centre: the nodes' centroid unless given (a distributed system
/// passes one centre to every rank, so that the ranks' rows form global modes).
/// Translations need no vectors: systems AMG interpolates each displacement
/// component separately and keeps constants. BoomerAMG's interpolation vectors
/// (linalg/boomeramg.hpp, interp_vec_variant).
Eigen::MatrixXd rigid_rotations(const MeshView& d, const Eigen::Vector3d* centre = nullptr);

}  // namespace hofem
