// Reading and validating scene files (scene.hpp gives the format).
#include "scene/scene.hpp"

#include "dynamics/integrator.hpp"
#include "material/material.hpp"
#include "io/input_file.hpp"
#include "scene/json_input.hpp"
#include "linalg/boomeramg_variants.hpp"
#include "solver/solver_spec.hpp"
#include "basis/element_orders.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <set>
#include <string_view>

namespace hofem {

namespace {

using json = nlohmann::json;

// The keys "box", "tube", "torus" and "file" of a mesh or embedded geometry (exactly one).
void parse_shape(const Field& m, SceneShape& shape, const std::string& scene_file) {
  if (m.has("box") + m.has("file") + m.has("tube") + m.has("torus") != 1)
    m.fail("needs exactly one of 'box', 'tube', 'torus' and 'file'");
  if (m.has("torus")) {
    const Field t = m.at("torus");
    t.keys({"major_radius", "r_in", "r_out", "cells"});
    shape.torus = true;
    shape.tube_r_in = t.at("r_in").number(0.0, 1e300, true);
    shape.tube_r_out = t.at("r_out").number(shape.tube_r_in, 1e300, true);
    shape.torus_major_radius = t.at("major_radius").number(shape.tube_r_out, 1e300, true);
    const Field c = t.at("cells");
    if (!c.raw().is_array() || c.raw().size() != 3)
      c.fail("must be an array of 3 integers (radial, around z, around the tube)");
    shape.cells << c.item(0).integer(1, 1000), c.item(1).integer(3, 10000), c.item(2).integer(3, 10000);
  } else if (m.has("tube")) {
    const Field t = m.at("tube");
    t.keys({"r_in", "r_out", "height", "cells", "curved"});
    shape.tube = true;
    if (t.has("curved")) shape.tube_curved = t.at("curved").boolean();
    shape.tube_r_in = t.at("r_in").number(0.0, 1e300, true);
    shape.tube_r_out = t.at("r_out").number(shape.tube_r_in, 1e300, true);
    shape.tube_height = t.at("height").number(0.0, 1e300, true);
    const Field c = t.at("cells");
    if (!c.raw().is_array() || c.raw().size() != 3) c.fail("must be an array of 3 integers (radial, around, along z)");
    shape.cells << c.item(0).integer(1, 1000), c.item(1).integer(3, 10000), c.item(2).integer(1, 1000);
  } else if (m.has("box")) {
    const Field b = m.at("box");
    b.keys({"min", "max", "cells"});
    shape.box_min = b.at("min").vec3();
    shape.box_max = b.at("max").vec3();
    if (!(shape.box_max.array() > shape.box_min.array()).all()) b.fail("needs max > min in every coordinate");
    const Field c = b.at("cells");
    if (!c.raw().is_array() || c.raw().size() != 3) c.fail("must be an array of 3 integers");
    for (int i = 0; i < 3; ++i) shape.cells[i] = c.item(i).integer(1, 1000);
  } else {
    shape.file = m.at("file").string();
    if (shape.file.empty()) m.at("file").fail("must name a .msh file");
    // Relative paths are relative to the scene file.
    if (std::filesystem::path(shape.file).is_relative() && !scene_file.empty())
      shape.file = (std::filesystem::path(scene_file).parent_path() / shape.file).string();
  }
}

// Refuses a generated mesh over the caps before anything is allocated: elements
// (6 tets or 1 hex per cell) and nodes (the order-p lattice of the cells'
// corners, an upper bound for the tube and the serendipity Hex20).
void check_generated_size(const Field& f, const SceneShape& shape, CellType cell, int order) {
  if (!f.has("box") && !f.has("tube") && !f.has("torus")) return;
  const long long nx = shape.cells.x(), ny = shape.cells.y(), nz = shape.cells.z();
  const long long elements = nx * ny * nz * (cell == CellType::Tetrahedron ? 6 : 1);
  const long long nodes = (order * nx + 1) * (order * ny + 1) * (order * nz + 1);
  const std::string excess = mesh_size_excess(elements, nodes);
  if (!excess.empty())
    f.at(f.has("box") ? "box" : f.has("tube") ? "tube" : "torus").at("cells").fail(fmt::format("= [{}, {}, {}] ({} {}): {}", nx, ny, nz,
                                                                      cell == CellType::Tetrahedron ? "tet" : "hex",
                                                                      order, excess));
}

// "solver": {"distributed": {...}}: hypre's Krylov method and BoomerAMG for
// runs with --distributed (the options `hofem mms` takes as --krylov, --amg, --rigid-body-modes).
void parse_distributed_solver(const Field& f, DistributedSolverOptions& o) {
  f.keys({"krylov", "amg", "rigid_body_modes", "gmres_restart"});
  if (f.has("krylov")) o.krylov = f.at("krylov").choice({"pcg", "gmres"});
  if (f.has("amg")) o.amg = f.at("amg").choice(boomeramg_variant_names());
  if (f.has("rigid_body_modes")) o.rigid_body_modes = f.at("rigid_body_modes").boolean();
  if (f.has("gmres_restart")) o.gmres_restart = f.at("gmres_restart").integer(1, 100000);
}

void parse_mesh(const Field& m, Scene& s) {
  m.keys({"box", "tube", "torus", "file", "cell", "order"});
  parse_shape(m, s.mesh, s.file);
  // The generators take a cell type; a .msh file brings its own.
  if (m.has("cell")) {
    if (m.has("file")) m.at("cell").fail("is given by the .msh file; remove it");
    s.cell = m.at("cell").choice({"tet", "hex"}) == "hex" ? CellType::Hexahedron : CellType::Tetrahedron;
  }
  s.order = m.has("order") ? m.at("order").integer(1, std::min(max_element_order(s.cell), input_limits().order)) : 1;
  check_generated_size(m, s.mesh, s.cell, s.order);
}

// "embedded": the geometry (Tet4 generators or a .msh of tets) and the finite-cell settings.
void parse_embedded(const Field& e, const Field& mesh, Scene& s) {
  e.keys({"box", "tube", "torus", "file", "drop_fraction", "stabilisation", "simplify", "stiffness_degree"});
  SceneEmbedded emb;
  parse_shape(e, emb.shape, s.file);
  if (e.has("drop_fraction")) emb.drop_fraction = e.at("drop_fraction").number(0.0, 1.0, false, true);
  if (e.has("stabilisation")) emb.stabilisation = e.at("stabilisation").number(0.0, 1.0);
  if (e.has("simplify")) emb.simplify = e.at("simplify").boolean();
  if (e.has("stiffness_degree")) emb.stiffness_degree = e.at("stiffness_degree").integer(1, 20);
  check_generated_size(e, emb.shape, CellType::Tetrahedron, 1);
  // The cut-cell rules need affine background cells: the tube's are curved (order
  // 2) or not parallelepipeds (Hex8), so only a box grid or a straight .msh will do.
  if (s.mesh.tube || s.mesh.torus)
    mesh.at(s.mesh.tube ? "tube" : "torus")
        .fail("cannot be the background of an embedded scene (its cells are not affine); use 'box'");
  s.embedded = std::move(emb);
}

void parse_boundary(const Field& b, Scene& s) {
  if (!b.raw().is_array()) b.fail("must be an array of {\"nodes\", \"motion\"} objects");
  if (static_cast<long long>(b.raw().size()) > input_limits().boundary_entries)
    b.fail(fmt::format("has {} entries, over the cap of {} (raise it with --limit boundary-entries=N)", b.raw().size(),
                       input_limits().boundary_entries));
  for (size_t i = 0; i < b.raw().size(); ++i) {
    const Field e = b.item(i);
    e.keys({"nodes", "motion", "release"});
    SceneBoundary bc;
    const Field nodes = e.at("nodes");
    if (nodes.raw().is_string()) {
      bc.set = nodes.string();
    } else {
      nodes.keys({"box"});
      const Field box = nodes.at("box");
      box.keys({"min", "max"});
      bc.box = std::make_pair(box.at("min").vec3(), box.at("max").vec3());
    }
    const Field motion = e.at("motion");
    if (motion.raw().is_string()) {
      bc.motion = motion.choice({"fixed"});
    } else {
      motion.keys({"translate", "rotate"});
      if (motion.raw().size() != 1) motion.fail("needs exactly one of 'translate' and 'rotate'");
      if (motion.has("translate")) {
        const Field t = motion.at("translate");
        t.keys({"velocity", "until"});
        bc.motion = "translate";
        bc.velocity = t.at("velocity").vec3();
        if (t.has("until")) bc.until = t.at("until").number(0.0, 1e300);
      } else {
        const Field r = motion.at("rotate");
        r.keys({"point", "axis", "omega", "until", "velocity"});
        bc.motion = "rotate";
        bc.point = r.at("point").vec3();
        bc.axis = r.at("axis").vec3();
        if (!(bc.axis.norm() > 0.0)) r.at("axis").fail("must be a non-zero vector");
        bc.omega = r.at("omega").number(-1e6, 1e6);
        if (r.has("until")) bc.until = r.at("until").number(0.0, 1e300);
        if (r.has("velocity")) bc.velocity = r.at("velocity").vec3();
      }
    }
    if (e.has("release")) bc.release = e.at("release").number(0.0, 1e300);
    s.boundary.push_back(bc);
  }
}


// Applies one "key.path=VALUE" override to the scene's JSON (scene.hpp).
void apply_override(json& root, const std::string& item, const std::string& origin) {
  const std::size_t eq = item.find('=');
  if (eq == std::string::npos || eq == 0)
    throw SceneError(fmt::format("{}: override '{}' is not key.path=VALUE", origin, item));
  const std::string path = item.substr(0, eq), text = item.substr(eq + 1);
  json value = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (value.is_discarded()) value = text;  // mesh.cell=hex: a bare word is a string
  json* at = &root;
  std::size_t start = 0;
  for (;;) {
    const std::size_t dot = path.find('.', start);
    const std::string key = path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    const std::string so_far = path.substr(0, dot == std::string::npos ? path.size() : dot);
    if (key.empty()) throw SceneError(fmt::format("{}: override '{}': empty key in '{}'", origin, item, path));
    const bool index = key.find_first_not_of("0123456789") == std::string::npos && key.size() < 10;
    if (index && at->is_array()) {
      const std::size_t i = std::stoul(key);
      if (i >= at->size())
        throw SceneError(fmt::format("{}: override '{}': {} is past the end of an array of {}", origin, item, so_far,
                                     at->size()));
      at = &(*at)[i];
    } else if (at->is_object() || at->is_null()) {
      // A new key is added (and a missing parent object made: "solver.linear=cholmod"
      // in a scene without "solver"), then validated like any other.
      at = &(*at)[key];
    } else {
      throw SceneError(fmt::format("{}: override '{}': {} is inside a value that is not an object", origin, item,
                                   so_far));
    }
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  *at = std::move(value);
}

Scene parse_validated(const json& j, const std::string& origin) {
  Scene s;
  s.file = origin;
  const Field root(j, "", origin);
  root.keys({"$schema", "name", "mesh", "material", "integrator", "dt", "duration", "mass", "lumping", "solver",
             "gravity", "damping", "boundary", "floor", "initial_velocity", "output", "embedded"});
  // "$schema": an editor's pointer to scene.schema.json (completion, checks while typing); not used here.
  if (root.has("$schema")) root.at("$schema").string();
  s.name = root.has("name") ? root.at("name").string() : std::filesystem::path(origin).stem().string();
  parse_mesh(root.at("mesh"), s);
  if (root.has("embedded")) parse_embedded(root.at("embedded"), root.at("mesh"), s);

  const Field mat = root.at("material");
  mat.keys({"model", "young", "poisson", "density"});
  s.material = mat.at("model").choice(material_names());
  s.young = mat.at("young").number(0.0, 1e300, true);
  s.poisson = mat.at("poisson").number(-1.0, 0.5, true, true);
  s.density = mat.has("density") ? mat.at("density").number(0.0, 1e300, true) : 1000.0;

  std::vector<std::string> integrators = integrator_names();
  integrators.push_back("static");
  const std::string integrator = root.at("integrator").choice(integrators);
  s.is_static = integrator == "static";
  DynamicsOptions& d = s.dynamics;
  if (!s.is_static) {
    d.integrator = parse_integrator(integrator);
    d.dt = root.at("dt").number(0.0, 1e300, true);
    s.duration = root.at("duration").number(0.0, 1e300, true);
  } else {
    for (const char* k : {"dt", "duration", "mass", "lumping", "damping", "floor", "initial_velocity", "output"})
      if (root.has(k)) root.at(k).fail("does not apply to a static scene; remove it");
  }
  d.density = s.density;
  if (root.has("mass"))
    d.mass = root.at("mass").choice({"lumped", "consistent"}) == "lumped" ? MassKind::Lumped : MassKind::Consistent;
  if (root.has("lumping"))
    d.lumping = root.at("lumping").choice({"row-sum", "hrz"}) == "hrz" ? MassLumping::HRZ : MassLumping::RowSum;
  if (root.has("solver")) {
    const Field sv = root.at("solver");
    sv.keys({"linear", "krylov_iterations", "krylov_max_iterations", "setup_reuse", "distributed", "newton_rtol",
             "newton_max_iterations", "eisenstat_walker", "hessian"});
    if (sv.has("linear")) {
      std::vector<std::string> names = linear_solver_names();
      names.insert(names.begin(), "auto");
      d.solver = SolverSpec::parse(sv.at("linear").choice(names));
    }
    if (sv.has("krylov_iterations")) {
      if (s.is_static)
        sv.at("krylov_iterations").fail("is for time-stepping scenes (a static solve runs to its tolerance)");
      d.solver.fixed_iterations = sv.at("krylov_iterations").integer(1, 100000);
      if (!d.solver.is_krylov())
        sv.at("krylov_iterations")
            .fail(fmt::format("needs solver.linear = a Krylov method (cg+, cr+, minres+, gmres+ with a "
                              "preconditioner), not \"{}\"",
                              d.solver.name()));
    }
    if (sv.has("krylov_max_iterations"))
      d.solver.krylov.max_iterations = sv.at("krylov_max_iterations").integer(1, 100000);
    if (sv.has("setup_reuse")) {  // "never", "amortised" or a growth factor >= 1 (solver_spec.hpp)
      const Field f = sv.at("setup_reuse");
      if (f.raw().is_number()) {
        d.solver.krylov.setup_reuse = SetupReuse::Growth;
        d.solver.krylov.setup_reuse_growth = f.number(1.0, 1e6);
      } else {
        d.solver.krylov.setup_reuse = f.choice({"never", "amortised"}) == "never" ? SetupReuse::Never : SetupReuse::Amortised;
      }
    }
    if (sv.has("distributed")) parse_distributed_solver(sv.at("distributed"), d.solver.distributed);
    if (sv.has("newton_rtol")) d.newton.rtol = sv.at("newton_rtol").number(0.0, 1.0, true, true);
    if (sv.has("newton_max_iterations")) d.newton.max_iterations = sv.at("newton_max_iterations").integer(1, 10000);
    if (sv.has("eisenstat_walker")) d.newton.eisenstat_walker = sv.at("eisenstat_walker").boolean();
    if (sv.has("hessian")) d.newton.project_psd = sv.at("hessian").choice({"as-assembled", "projected"}) == "projected";
  }
  if (root.has("gravity")) d.gravity = root.at("gravity").vec3();
  if (root.has("damping")) {
    const Field dm = root.at("damping");
    dm.keys({"alpha", "beta"});
    if (dm.has("alpha")) d.rayleigh_alpha = dm.at("alpha").number(0.0, 1e300);
    if (dm.has("beta")) d.rayleigh_beta = dm.at("beta").number(0.0, 1e300);
  }
  if (root.has("floor")) {
    const Field f = root.at("floor");
    f.keys({"height", "normal", "stiffness"});
    Floor floor;
    if (f.has("height")) floor.height = f.at("height").number(-1e300, 1e300);
    if (f.has("normal")) {
      floor.normal = f.at("normal").vec3();
      if (!(floor.normal.norm() > 0.0)) f.at("normal").fail("must be a non-zero vector");
    }
    floor.stiffness = f.at("stiffness").number(0.0, 1e300, true);
    d.floor = floor;
  }
  if (root.has("boundary")) parse_boundary(root.at("boundary"), s);
  if (root.has("initial_velocity")) s.initial_velocity = root.at("initial_velocity").vec3();
  if (root.has("output")) {
    const Field o = root.at("output");
    o.keys({"every"});
    s.output_every = o.at("every").integer(1, 1000000000);
  }
  return s;
}

// An override's key path as the parser's messages write it: "boundary.0.nodes" is
// "boundary[0].nodes" there (json_input's Field paths).
std::string message_path(const std::string& path) {
  std::string out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t dot = path.find('.', start);
    const std::string key = path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    const bool index = !key.empty() && key.find_first_not_of("0123456789") == std::string::npos;
    out += index ? "[" + key + "]" : (out.empty() ? key : "." + key);
    if (dot == std::string::npos) return out;
    start = dot + 1;
  }
}

// Whether `message` holds `lead` (a key path after "FILE: " or "key '") followed
// by its end, a space, a dot, a quote or an index: the key or a key inside it.
bool names_key(const std::string& message, const std::string& lead) {
  for (std::size_t at = message.find(lead); at != std::string::npos; at = message.find(lead, at + 1)) {
    const std::size_t end = at + lead.size();
    if (end == message.size() || std::string_view(" .'[").find(message[end]) != std::string_view::npos) return true;
  }
  return false;
}

// The override (if any) that set the key an error names: a reader who typed
// `--set mesh.order=abc` (or a study's run list) must see that the bad value is
// theirs, not the file's. The error names its key path after "FILE: " or inside
// "key '...'"; the longest override path that is that key or a parent of it wins.
// An unknown key is also the override's when the override's path passes through
// it ("mesh.boxx.min=..." made the unknown key 'mesh.boxx').
std::string override_named_by(const std::string& message, const std::string& origin,
                              const SceneOverrides& overrides) {
  const std::string* best = nullptr;
  std::size_t best_len = 0;
  for (const std::string& item : overrides) {
    const std::size_t eq = item.find('=');
    if (eq == std::string::npos || eq == 0 || eq <= best_len) continue;
    const std::string path = message_path(item.substr(0, eq));
    bool named = names_key(message, origin + ": " + path) || names_key(message, "key '" + path);
    for (std::size_t cut = path.size(); !named && cut != std::string::npos && cut > 0;
         cut = path.find_last_of(".[", cut - 1))
      named = message.find("key '" + path.substr(0, cut) + "' is unknown") != std::string::npos;
    if (named) {
      best = &item;
      best_len = eq;
    }
  }
  return best ? *best : std::string();
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& origin, const SceneOverrides& overrides) {
  check_nesting(text, origin);
  json j = parse_json(text, origin);
  for (const std::string& o : overrides) apply_override(j, o, origin);
  try {
    Scene s = parse_validated(j, origin);
    s.overrides = overrides;
    s.resolved = j.dump();
    return s;
  } catch (const SceneError& e) {
    throw SceneError(name_override(e.what(), origin, overrides));
  }
}

std::string name_override(const std::string& message, const std::string& origin, const SceneOverrides& overrides) {
  const std::string item = override_named_by(message, origin, overrides);
  if (item.empty()) return message;
  return fmt::format("{} (the value comes from the override '{}')", message, item);
}

Scene read_scene(const std::string& path, const SceneOverrides& overrides) {
  return parse_scene(read_json_file(path, "the scene file"), path == "-" ? "<stdin>" : path, overrides);
}

}  // namespace hofem
