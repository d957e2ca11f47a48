#pragma once
// What a mesh-aware preconditioner may know about the system besides its matrix:
// the mesh (elements, vertices, order) and the map from global DOFs to the free
// numbering of the matrix. Purely algebraic preconditioners ignore it; the
// p-multigrid (needs the order-1 space of the same mesh) and the element-block
// Additive-Schwarz preconditioner (needs each element's DOFs) require it.
#include "assembly/dof_map.hpp"
#include "mesh/mesh.hpp"

namespace hofem {

struct Discretization {
  const Mesh* mesh = nullptr;
  const DofMap* dofs = nullptr;
  bool valid() const { return mesh != nullptr && dofs != nullptr; }
};

}  // namespace hofem
