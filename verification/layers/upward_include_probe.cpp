// Compiled as a source of the mesh layer (hofem_mesh's include path) by ctest
// layers.upward_include_fails, which expects the build to fail on the include
// below: mesh/ sits under solver/, so solver's headers are not on its path.
// Not part of any default build target.
#include "mesh/mesh.hpp"
#include "solver/newton.hpp"

int upward_include_probe() { return hofem::Mesh{}.num_nodes(); }
