// A scene's meshes (the simulated one and the embedded geometry) built from
// generators or .msh files and validated, and the node sets its boundary
// entries select. Parsing the file is scene_parser.cpp's job; this file turns
// the parsed description into meshes.
#include "scene/scene_mesh.hpp"

#include "io/gmsh_reader.hpp"
#include "mesh/box_mesh.hpp"
#include "mesh/mesh_quality.hpp"
#include "mesh/mesh_reorient.hpp"
#include "mesh/mesh_upgrade.hpp"
#include "mesh/node_selection.hpp"
#include "mesh/tube_mesh.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <ranges>
#include <stdexcept>

namespace hofem {

namespace {

// Every error here names the scene and a key; when a --set override (or a study's
// run) set that key, the message says so, as the parser's do.
[[noreturn]] void fail(const Scene& s, const std::string& message) {
  throw SceneError(name_override(message, s.file, s.overrides));
}

// The scene's mesh `key` after --reorient's flips (announced on stderr, never
// silent) and validation; errors name the scene, the key and the element.
Mesh validated(Mesh mesh, const Scene& s, const char* key) {
  if (s.reorient) {
    const std::vector<int> flipped = reorient_inverted_elements(mesh);
    if (!flipped.empty())
      fmt::print(stderr, "hofem: warning: {}: {}: --reorient renumbered {} inverted element(s), the first {}\n", s.file,
                 key, flipped.size(), describe_element(mesh, flipped.front()));
  }
  try {
    validate_mesh(mesh);
  } catch (const MeshError& e) {
    fail(s, fmt::format("{}: {}: {}", s.file, key, e.what()));
  }
  return mesh;
}

// The mesh of `shape`: the torus, tube or box generator's of this cell and order,
// or the .msh file as read (a read error names the scene and `key`.file).
Mesh generated_or_read(const SceneShape& g, CellType cell, int order, const Scene& s, const char* key) {
  if (g.torus)
    return hollow_torus_mesh(g.torus_major_radius, g.tube_r_in, g.tube_r_out, g.cells.x(), g.cells.y(), g.cells.z(),
                             cell, order);
  if (g.tube)
    return hollow_cylinder_mesh(g.tube_r_in, g.tube_r_out, g.tube_height, g.cells.x(), g.cells.y(), g.cells.z(), cell,
                                order, g.tube_curved);
  if (g.file.empty())
    return box_mesh(BoxSpec{{g.box_min.x(), g.box_min.y(), g.box_min.z()},
                            {g.box_max.x(), g.box_max.y(), g.box_max.z()},
                            {g.cells.x(), g.cells.y(), g.cells.z()}},
                    cell, order);
  try {
    return read_gmsh(g.file);
  } catch (const std::exception& e) {
    fail(s, fmt::format("{}: {}.file: {}", s.file, key, e.what()));
  }
}

}  // namespace

Mesh build_scene_mesh(const Scene& s) {
  Mesh mesh = generated_or_read(s.mesh, s.cell, s.order, s, "mesh");
  if (mesh.order != s.order) {  // a .msh file's own order
    if (mesh.order != 1 || mesh.cell != CellType::Tetrahedron)
      fail(s, fmt::format("{}: mesh.order = {}: the mesh '{}' has order {}; only P1 tetrahedra are upgraded",
                                   s.file, s.order, s.mesh.file, mesh.order));
    mesh = upgrade_order(mesh, s.order);
  }
  return validated(std::move(mesh), s, "mesh");
}

Mesh build_embedded_mesh(const Scene& s) {
  if (!s.embedded) throw std::logic_error("build_embedded_mesh: the scene has no embedded geometry");
  // Generators: Tet4 (box_mesh of order 1 is box_tet_mesh).
  Mesh mesh = generated_or_read(s.embedded->shape, CellType::Tetrahedron, 1, s, "embedded");
  if (mesh.cell != CellType::Tetrahedron)
    fail(s,
         fmt::format("{}: embedded.file: '{}' is not a tetrahedral mesh (the embedded geometry must be tetrahedra)",
                    s.file, s.embedded->shape.file));
  return validated(std::move(mesh), s, "embedded");
}

std::vector<int> boundary_nodes(const Scene& s, const Mesh& mesh, size_t index) {
  const SceneBoundary& b = s.boundary.at(index);
  std::vector<int> nodes;
  if (!b.set.empty()) {
    const auto it = mesh.node_sets.find(b.set);
    if (it == mesh.node_sets.end()) {
      fail(s, fmt::format("{}: boundary[{}].nodes = '{}' is not a node set of the mesh (valid: {})", s.file,
                                   index, b.set, fmt::join(std::views::keys(mesh.node_sets), ", ")));
    }
    nodes = it->second;
  } else {
    nodes = nodes_in_box(mesh, b.box->first, b.box->second);
  }
  if (nodes.empty()) fail(s, fmt::format("{}: boundary[{}].nodes selects no node of the mesh", s.file, index));
  return nodes;
}

}  // namespace hofem
