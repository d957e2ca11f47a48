#pragma once
// Raising the order of a linear mesh (thesis §5.4): a Tet4 mesh becomes Tet(p)
// for any p >= 2, a Hex8 mesh becomes Hex20, with every edge, face and interior
// node created once and shared by all elements that touch it.
//
// Sharing and orientation are handled by naming each new node by what it *is*,
// not by where it sits in one element: a lattice point of an order-p element has
// integer barycentric coordinates (l_0..l_3), sum p, on the element's vertices
// (g_0..g_3); its key is the sorted list of pairs (g_a, l_a) with l_a > 0. Two
// elements sharing an edge or face produce the same key for the same point
// whatever their local vertex order, so neighbouring edge/face nodes match by
// construction. Geometry is straight-sided: x = sum_a (l_a / p) X_{g_a}.
#include "mesh/mesh.hpp"

namespace hofem {

/// Order-p copy of a linear (order 1) mesh. Vertex ids are kept (0..V-1) and the
/// new nodes follow. Node sets: a set with an element set of the same name (a
/// volume group) gets every node of those elements; any other set gains a new
/// node when every vertex of its key is in the set and those vertices lie
/// together on one boundary face (so surface and curve groups gain their edge
/// and face nodes, and an interior edge between two boundary vertices does not).
/// "boundary" is rebuilt topologically (faces used by one element).
Mesh upgrade_order(const Mesh& linear, int order);

}  // namespace hofem
