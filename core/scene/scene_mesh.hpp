#pragma once
// A scene's meshes and boundary node sets (scene_mesh.cpp says how).
#include "mesh/mesh.hpp"
#include "scene/scene.hpp"

#include <cstddef>
#include <vector>

namespace hofem {

/// Builds the scene's mesh (generator or .msh, upgraded to the order) and
/// validates it: an inverted or degenerate element is a SceneError naming the
/// scene, the key, the .msh file and the element's tag and line.
Mesh build_scene_mesh(const Scene& scene);
/// The embedded geometry's tetrahedral mesh (generators: Tet4; a .msh as read,
/// any order); throws SceneError naming embedded.file if it cannot be read or is
/// not tetrahedral. Requires scene.embedded.
Mesh build_embedded_mesh(const Scene& scene);
/// The node ids a boundary entry selects; throws SceneError if none.
std::vector<int> boundary_nodes(const Scene& scene, const Mesh& mesh, size_t index);

}  // namespace hofem
