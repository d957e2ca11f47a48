#pragma once
// `--reorient`: renumbers the nodes of straight inverted elements so that their
// Jacobian turns positive. An element whose det J is negative at every
// validation point and whose nodes all sit where its vertices' linear map puts
// them has merely been numbered the wrong way round (a left-handed vertex
// order); the mirror image of its node numbering - swap reference x and y, which
// maps the reference cell and its Lagrange nodes onto themselves - is the same
// element with det J > 0. Curved or folded elements are not touched: no
// renumbering makes them valid, and validate_mesh still rejects them.
#include "mesh/mesh.hpp"

#include <vector>

namespace hofem {

/// Flips every straight element whose det J is negative at all its validation
/// points; returns the flipped elements' indices (the caller warns, naming them
/// with describe_element).
std::vector<int> reorient_inverted_elements(Mesh& mesh);

}  // namespace hofem
