#pragma once
// Selecting nodes of a mesh by where they are.
#include "mesh/mesh.hpp"

#include <Eigen/Core>

#include <vector>

namespace hofem {

/// The nodes inside the closed box [lo, hi], with a tolerance of 1e-9 times
/// the mesh's bounding-box diagonal so that a box drawn on a face of the mesh
/// catches the face's nodes despite rounding in the coordinates.
std::vector<int> nodes_in_box(const Mesh& mesh, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);

}  // namespace hofem
