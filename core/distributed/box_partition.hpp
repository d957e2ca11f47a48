#pragma once
// One rank's piece of a structured box mesh, generated directly: no
// rank ever builds the whole mesh, so the input costs memory in proportion to
// the piece, not to the problem (the sizing model's "replicated input" R = 0).
//
// Partition: recursive bisection of the box's cubes, the same coordinate
// bisection partition_elements() does on element centroids, but on the cube
// lattice: the longest side of a block (in length) is cut at the cube layer that
// splits the block's cubes in proportion to the parts on each side. Every cube
// (and the 6 Kuhn tets or the hexahedron in it) belongs to one part.
//
// Global node ids are lattice indices: every node of the order-p tet mesh (and
// of Hex8 / Hex20) sits on the box's lattice refined q times (q = p for tets,
// 2 for Hex20, 1 for Hex8), and id = I + (q nx + 1) (J + (q ny + 1) K). For tets
// every lattice point is a node (the Kuhn simplices are unimodular); for Hex20
// the face and cube centres are not, so ids there have gaps. A node's owner is
// the lowest part among the cubes whose closure holds it, as node_owners() would
// say on the whole mesh. Coordinates are computed from the lattice index with
// one formula on every rank, so shared nodes agree bitwise.
#include "mesh/box_mesh.hpp"
#include "distributed/local_mesh.hpp"

#include <array>
#include <vector>

namespace hofem {

/// Cube index ranges [lo, hi) per direction of each part, by recursive bisection.
/// Throws MeshError if the box has fewer cubes than parts along a cut.
std::vector<std::array<std::array<int, 2>, 3>> box_blocks(const BoxSpec& box, int parts);

/// Part p's piece of box_mesh(box, cell, order) partitioned into `parts` blocks.
/// Node sets: "boundary", "xmin", ..., "zmax" of the whole box (not of the block).
LocalMesh box_piece(const BoxSpec& box, CellType cell, int order, int parts, int p);

}  // namespace hofem
