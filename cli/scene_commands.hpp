#pragma once
// `hofem run`'s modes besides running (scene_commands.cpp): --print-defaults and
// --check; a real run goes on to run_scene_file (commands.cpp).
#include "commands.hpp"

namespace hofem::cli {

/// --print-defaults: prints the default scene (core/scene/scene_defaults.hpp), exit 0.
/// --check: validates SCENE with its --set overrides, builds its meshes and boundary
/// selections, prints "SCENE: valid" and a summary, exit 0; an invalid scene is a
/// UsageError (exit 2) naming the file and key. Otherwise: run_scene_file, which
/// needs --out.
int run_scene_command(const RunOptions& o);

}  // namespace hofem::cli
