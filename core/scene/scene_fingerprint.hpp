#pragma once
// What identifies a run's result: the scene as resolved (its JSON after the
// overrides), the command line's --reorient, and the bytes of the mesh and
// geometry files it reads. Checkpoints and a study's stored runs are keyed by
// it, so that a changed key, override or mesh file is never taken for a
// finished run.
#include "scene/scene.hpp"

#include <string>

namespace hofem {

/// 16 hex digits (FNV-1a 64 over the parts above). Throws SceneError naming a
/// mesh or geometry file that cannot be read.
std::string scene_fingerprint(const Scene& s);

}  // namespace hofem
