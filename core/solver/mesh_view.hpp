#pragma once
// What a mesh-aware preconditioner may know about the system besides its matrix:
// the mesh (elements, vertices, order) and the map from global DOFs to the free
// numbering of the matrix. Purely algebraic preconditioners ignore it; the
// p-multigrid (needs the order-1 space of the same mesh) and the element-block
// Additive-Schwarz preconditioner (needs each element's DOFs) require it.
#include "assembly/dof_map.hpp"
#include "mesh/mesh.hpp"

#include <vector>

namespace hofem {

/// The mesh and DOF map of a system, as a preconditioner sees them (not
/// owned). Discretization (solver/discretization.hpp) is what owns them.
struct MeshView {
  const Mesh* mesh = nullptr;
  const DofMap* dofs = nullptr;
  /// Elements that need a block of their own in block preconditioners (the
  /// finite cell method's cut cells under a volume-fraction threshold, Longva
  /// et al. 2020 §5.2); null: every element. Non-null and empty: none (diagonal only).
  const std::vector<int>* block_elements = nullptr;
  bool valid() const { return mesh != nullptr && dofs != nullptr; }
};

}  // namespace hofem
