#pragma once
// The embedded body of the finite cell convergence and load checks (Longva et al. 2020
// Fig. 10 uses a hemisphere-like body in hex grids): a half ball of radius 1/2
// about (1/2, 1/2, 0) as a tet mesh, its flat face in the grid plane z = 0.
#include "mesh/mesh.hpp"

namespace hofem::verification {

/// The tet mesh of [-1,1]^2 x [0,1] (2k x 2k x k Kuhn cubes) pushed radially onto
/// the ball (X |X|_inf / |X|_2), a map that keeps the plane z = 0 and sends the
/// cube's boundary onto the sphere, then scaled by 1/2 and moved to (1/2, 1/2, 0).
/// k = 4: 1536 tets, 512 triangles on the curved surface.
Mesh half_ball(int k);

/// The curved part of a half ball's boundary (boundary_surface without the
/// triangles of the flat face z = 0), outward triangles.
Mesh half_ball_curved_surface(const Mesh& half_ball);

}  // namespace hofem::verification
