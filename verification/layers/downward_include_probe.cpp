// The control of upward_include_probe.cpp: the same kind of mesh-layer source
// including only layers under mesh/ (ctest layers.downward_include_builds), so
// that the upward probe's failure is the include's and not the set-up's.
#include "basis/reference_basis.hpp"
#include "mesh/mesh.hpp"
#include "quadrature/cell_type.hpp"

int downward_include_probe() { return hofem::Mesh{}.num_nodes(); }
