// Compiled as a source of the linalg layer (hofem_linalg's include path) by
// ctest layers.linalg_includes_no_mesh, which expects the build to fail on the
// include below: linear algebra knows matrices and vectors only, so no mesh,
// basis or element header is on its path.
// Not part of any default build target.
#include "linalg/sparse_matrix.hpp"
#include "mesh/mesh.hpp"

int linalg_mesh_include_probe() { return hofem::Mesh{}.num_nodes(); }
