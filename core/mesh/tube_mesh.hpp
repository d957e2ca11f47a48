#pragma once
// A hollow cylinder (tube) about the z axis: the box generator's mesh of the
// parameter box [r_in, r_out] x [0, 2 pi] x [0, height] mapped by
// (r, theta, z) -> (r cos theta, r sin theta, z), with the seam theta = 2 pi
// merged onto theta = 0. Higher-order nodes are mapped too, so the elements are
// curved (isoparametric) and follow the circles; with curved = false they are
// straight-sided instead (the linear tube's elements with the order raised by
// upgrade_order: the polygon's chords, as a tetrahedral mesher's Tet10 of a
// faceted surface is). Node sets: "inner", "outer", "bottom", "top" (and "boundary").
#include "mesh/mesh.hpp"

namespace hofem {

/// Throws std::invalid_argument unless 0 < r_in < r_out, height > 0, n_r, n_z >= 1, n_theta >= 3.
Mesh hollow_cylinder_mesh(double r_in, double r_out, double height, int n_r, int n_theta, int n_z, CellType cell,
                          int order, bool curved = true);

/// A hollow torus about the z axis: the box generator's mesh of the parameter box
/// [r_in, r_out] x [0, 2 pi] x [0, 2 pi] mapped by (r, theta, phi) ->
/// ((R + r cos phi) cos theta, (R + r cos phi) sin theta, r sin phi), both seams
/// merged. Curved (isoparametric) elements like the tube's; a body without edges
/// or corners, so a problem with Dirichlet data on "inner" and free "outer" has a
/// smooth solution (no edge singularity caps convergence rates). Node sets:
/// "inner", "outer", "boundary". Throws std::invalid_argument unless
/// 0 < r_in < r_out < R, n_r >= 1, n_theta, n_phi >= 3.
Mesh hollow_torus_mesh(double major_radius, double r_in, double r_out, int n_r, int n_theta, int n_phi, CellType cell,
                       int order);

}  // namespace hofem
