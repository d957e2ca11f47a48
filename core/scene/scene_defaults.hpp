#pragma once
// The default scene as JSON (`hofem run --print-defaults`): every key that has a
// fixed default, with the value a default-constructed Scene (scene.hpp) and its
// DynamicsOptions hold, so the printout cannot drift from the parser. Keys whose
// default depends on other keys (mass, lumping: on the integrator and order;
// name: the file's stem) and optional features that are off unless given (floor,
// embedded, solver.krylov_iterations) are left out. The required keys (mesh,
// material, integrator, dt, duration) take the struct's initial values. The
// result passes `hofem run --check`, and ctest schema.print_defaults checks it
// against the `default`s of scene.schema.json.
#include <nlohmann/json.hpp>

namespace hofem {

nlohmann::json default_scene_json();

}  // namespace hofem
