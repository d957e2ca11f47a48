// `hofem run --print-defaults | --check` and the usage rules of `hofem run` (scene_commands.hpp).
#include "scene_commands.hpp"

#include "dynamics/integrator.hpp"
#include "scene/scene.hpp"
#include "scene/scene_defaults.hpp"
#include "scene/scene_mesh.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <string>

namespace hofem::cli {

namespace {

// The one-line summary after "valid": what the overrides changed shows here
// (mesh size, order, time step), which is what ctest schema.set checks.
std::string summary(const Scene& s, const Mesh& mesh) {
  std::string out = fmt::format("{}: {} nodes, {} {} elements of order {}", s.name, mesh.num_nodes(),
                                mesh.num_elements(), s.cell == CellType::Hexahedron ? "hex" : "tet", s.order);
  if (s.embedded) out += " (background of an embedded geometry)";
  out += fmt::format("; material {}, young {}, poisson {}, density {}", s.material, s.young, s.poisson, s.density);
  if (s.is_static) return out + "; static";
  return out + fmt::format("; {}, dt {}, duration {}; {} boundary entries", integrator_name(s.dynamics.integrator),
                           s.dynamics.dt, s.duration, s.boundary.size());
}

int check_scene(const RunOptions& o) {
  try {
    Scene scene = read_scene(o.scene, o.set);
    scene.reorient = o.reorient;
    // A user checking a scene wants to know that it will start: the mesh file
    // exists and reads, its elements are valid, every boundary entry selects
    // nodes. Building the meshes is quick next to any run of them.
    const Mesh mesh = build_scene_mesh(scene);
    if (scene.embedded) build_embedded_mesh(scene);
    for (size_t i = 0; i < scene.boundary.size(); ++i) boundary_nodes(scene, mesh, i);
    fmt::print("{}: valid\n  {}\n", o.scene, summary(scene, mesh));
  } catch (const SceneError& e) {
    throw UsageError(e.what());
  }
  return 0;
}

}  // namespace

int run_scene_command(const RunOptions& o) {
  if (o.print_defaults) {
    if (!o.scene.empty() || o.check || !o.set.empty())
      throw UsageError("run --print-defaults takes no scene file, --check or --set");
    fmt::print("{}\n", default_scene_json().dump(2));
    return 0;
  }
  if (o.scene.empty()) throw UsageError("run needs a SCENE file (or --print-defaults)");
  if (o.check) {
    if (o.distributed || o.no_frames || !o.out.empty())
      throw UsageError("run --check validates only: --out, --no-frames and --distributed do not apply");
    apply_limits(o.limits);
    return check_scene(o);
  }
  if (o.out.empty()) throw UsageError("run needs --out DIR for its frames and stats.json (or --check to validate only)");
  if (o.final_frame && !o.no_frames)
    throw UsageError("run --final-frame goes with --no-frames (the frames already hold the last state)");
  return run_scene_file(o);
}

}  // namespace hofem::cli
