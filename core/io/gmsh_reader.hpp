#pragma once
// Reader for Gmsh .msh files, ASCII format 4.1 or 2.2, into a hofem::Mesh.
//
// What is kept:
//  - the volume elements, all of one type: Tet4 (Gmsh type 4), Tet10 (11), Tet20 (29),
//    Hex8 (5) or Hex20 (17). Node order is Gmsh's own, which is hofem's (core/basis).
//  - physical groups of any dimension become node sets: every node of the group's
//    elements, sorted, without duplicates, named by $PhysicalNames or
//    "physical_<tag>" when unnamed. Groups of different dimensions that share a name
//    (including two unnamed groups with the same tag) are merged into one set.
//    Physical volume groups also become element sets (indices into Mesh::elements).
//    A group listed in $PhysicalNames that has no elements gives an empty set.
//  - lower-dimensional elements (point 15; lines 1, 8, 26; triangles 2, 9, 21;
//    quads 3, 16) are read only for physical groups and then dropped.
//  - nodes used by a volume element or by an element of a physical group,
//    renumbered 0..N-1 in the order they appear in $Nodes; other nodes are dropped.
//
// Unknown sections ($Comments, $NodeData, $Periodic, ...) are skipped. Every
// malformed input throws MeshError("<origin>:<line>: <what is wrong>").
#include <string>
#include <string_view>

#include "mesh/mesh.hpp"

namespace hofem {

/// Reads the Gmsh mesh file at `path`; MeshError naming the path if it cannot be read.
Mesh read_gmsh(const std::string& path);

/// Parses the text of a .msh file; `origin` (a file name) prefixes every error message.
Mesh read_gmsh_text(std::string_view text, std::string_view origin);

}  // namespace hofem
