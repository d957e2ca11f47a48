#pragma once
// Partition quality: the recursive coordinate bisection of
// core/distributed/mesh_partition on structured boxes (Tet4/Tet10/Tet20, Hex8/Hex20)
// and hollow cylinders, K = 2, 4, 8 parts. Per case and K: every element in
// exactly one part, element counts balanced, every node owned once, and the
// ghost fraction and edge cut (cut faces) held to bounds derived from the cut
// planes RCB must find on these meshes (partition_checks.cpp says why). The
// per-part element, owned and ghost counts are written in each row's `why`.
// Groups "partition.*"; cheap (a few thousand elements per case).
#include "report.hpp"

namespace hofem::verification {

void add_partition_checks(Report& report);

}  // namespace hofem::verification
