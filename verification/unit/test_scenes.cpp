// Scene files: every key validated before work starts (errors name the file and
// the key, with the valid choices), the built-in scenes parse, and a run writes
// its frames, .pvd and stats.json while building only what the scene needs.
#include "assembly/assembler.hpp"
#include "embedded/embedded_quadrature.hpp"
#include "embedded/finite_cell_quadrature.hpp"
#include "mesh/tube_mesh.hpp"
#include "io/vtu_writer.hpp"
#include "scene/scene.hpp"
#include "scene/scene_mesh.hpp"
#include "scene/scene_embedding.hpp"
#include "scene/scene_runner.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

namespace hofem {
namespace {

const std::string kValid = R"({
  "mesh": {"box": {"min": [0, 0, 0], "max": [1, 1, 1], "cells": [1, 1, 1]}, "cell": "tet", "order": 1},
  "material": {"model": "neohookean", "young": 1e5, "poisson": 0.3, "density": 1000},
  "integrator": "implicit-euler", "dt": 0.01, "duration": 0.03,
  "boundary": [{"nodes": "zmin", "motion": "fixed"}]
})";

// The valid scene with one substring replaced.
std::string with(const std::string& from, const std::string& to) {
  std::string s = kValid;
  const size_t at = s.find(from);
  if (at == std::string::npos) throw std::logic_error("test scene lacks '" + from + "'");
  return s.replace(at, from.size(), to);
}

std::string error_of(const std::string& text) {
  try {
    parse_scene(text, "t.json");
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

TEST(Scenes, InvalidScenesNameTheFileAndTheKey) {
  struct Case {
    std::string text, expected;
  };
  const Case cases[] = {
      {with("\"integrator\"", "\"integrater\""), "t.json: key 'integrater' is unknown (valid: $schema, boundary, damping, dt,"},
      {with("\"young\"", "\"youngs\""), "t.json: key 'material.youngs' is unknown (valid: density, model, poisson, young)"},
      {with("\"poisson\": 0.3", "\"poisson\": 0.5"), "t.json: material.poisson = 0.5 is out of range (-1, 0.5)"},
      {with("\"young\": 1e5", "\"young\": -3"), "t.json: material.young = -3 is out of range (0,"},
      {with("\"dt\": 0.01", "\"dt\": \"fast\""), "t.json: dt must be a number (got \"fast\")"},
      {with("\"dt\": 0.01, ", ""), "t.json: key 'dt' is missing"},
      {with("\"neohookean\"", "\"rubber\""),
       "t.json: material.model = 'rubber' is not one of: linear, stvk, corotated, neohookean, stable-neohookean"},
      {with("\"implicit-euler\"", "\"verlet\""), "is not one of: explicit-euler, symplectic-euler, leapfrog, rk4,"},
      {with("\"cells\": [1, 1, 1]", "\"cells\": [1, 0, 1]"), "t.json: mesh.box.cells[1] = 0 is out of range [1, 1000]"},
      {with("\"cells\": [1, 1, 1]", "\"cells\": [1, 1.5, 1]"), "t.json: mesh.box.cells[1] must be an integer"},
      {with("\"max\": [1, 1, 1]", "\"max\": [1, 0, 1]"), "t.json: mesh.box needs max > min in every coordinate"},
      {with("\"cell\": \"tet\"", "\"cell\": \"prism\""), "t.json: mesh.cell = 'prism' is not one of: tet, hex"},
      {with("\"mesh\": {", "\"mesh\": {\"file\": \"a.msh\", "), "t.json: mesh needs exactly one of 'box', 'tube', 'torus' and 'file'"},
      {with("\"motion\": \"fixed\"", "\"motion\": \"glued\""), "t.json: boundary[0].motion = 'glued' is not one of: fixed"},
      {with("\"motion\": \"fixed\"", "\"motion\": {\"rotate\": {\"point\": [0,0,0], \"axis\": [0,0,0], \"omega\": 1}}"),
       "t.json: boundary[0].motion.rotate.axis must be a non-zero vector"},
      {with("\"boundary\"", "\"solver\": {\"linear\": \"magic\"}, \"boundary\""),
       "t.json: solver.linear = 'magic' is not one of: auto, cholmod,"},
      {with("\"boundary\"", "\"floor\": {\"height\": 0}, \"boundary\""), "t.json: key 'floor.stiffness' is missing"},
      {with("\"boundary\"", "\"gravity\": [0, 0], \"boundary\""), "t.json: gravity must be an array of 3 numbers"},
      {with("\"boundary\"", "\"output\": {\"every\": 0}, \"boundary\""), "t.json: output.every = 0 is out of range"},
      {with("\"implicit-euler\", \"dt\": 0.01, \"duration\": 0.03", "\"static\", \"dt\": 0.01"),
       "t.json: dt does not apply to a static scene; remove it"},
      {with("\"duration\": 0.03", "\"duration\": 0.03,"), "t.json: line 4: not valid JSON"},
      {"[1, 2]", "t.json: the scene must be an object"},
  };
  for (const Case& c : cases) {
    const std::string e = error_of(c.text);
    EXPECT_NE(e.find(c.expected), std::string::npos) << "expected: " << c.expected << "\n     got: " << e;
  }
  // A hex of order 3 is out of range for hex (Hex8, Hex20 only).
  EXPECT_NE(error_of(with("\"cell\": \"tet\", \"order\": 1", "\"cell\": \"hex\", \"order\": 3")).find("mesh.order = 3 is out of range [1, 2]"),
            std::string::npos);
  // Node sets are checked against the mesh before the run starts.
  const Scene s = parse_scene(with("\"zmin\"", "\"bottom\""), "t.json");
  const Mesh m = build_scene_mesh(s);
  try {
    boundary_nodes(s, m, 0);
    FAIL() << "an unknown node set was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("boundary[0].nodes = 'bottom' is not a node set of the mesh (valid: boundary, xmax"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(read_scene("/nonexistent/scene.json"), SceneError);
  // A missing mesh file is reported with the key that names it.
  const Scene missing = parse_scene(with("\"box\": {\"min\": [0, 0, 0], \"max\": [1, 1, 1], \"cells\": [1, 1, 1]}, \"cell\": \"tet\", ",
                                         "\"file\": \"/nonexistent/part.msh\", "),
                                    "t.json");
  try {
    build_scene_mesh(missing);
    FAIL() << "a missing mesh file was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("t.json: mesh.file: "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("/nonexistent/part.msh"), std::string::npos) << e.what();
  }
}

// solver.hessian chooses Newton's matrix: the Hessian as assembled by default,
// the PSD-projected one when asked (both spellings checked, an unknown one named).
TEST(Scenes, HessianKeyChoosesTheProjectedHessian) {
  EXPECT_FALSE(parse_scene(kValid, "t.json").dynamics.newton.project_psd);
  const std::string solver = R"("boundary":)";
  EXPECT_FALSE(parse_scene(with(solver, R"("solver": {"hessian": "as-assembled"}, "boundary":)"), "t.json")
                   .dynamics.newton.project_psd);
  EXPECT_TRUE(parse_scene(with(solver, R"("solver": {"hessian": "projected"}, "boundary":)"), "t.json")
                  .dynamics.newton.project_psd);
  EXPECT_NE(error_of(with(solver, R"("solver": {"hessian": "exact"}, "boundary":)")).find("solver.hessian"),
            std::string::npos);
}

// solver.krylov_max_iterations caps every Krylov solve of the run (5000 unless set).
TEST(Scenes, KrylovMaxIterationsCapsTheSolves) {
  EXPECT_EQ(parse_scene(kValid, "t.json").dynamics.solver.krylov.max_iterations, 5000);
  const std::string at = R"("boundary":)";
  EXPECT_EQ(parse_scene(with(at, R"("solver": {"krylov_max_iterations": 400}, "boundary":)"), "t.json")
                .dynamics.solver.krylov.max_iterations,
            400);
  EXPECT_NE(error_of(with(at, R"("solver": {"krylov_max_iterations": 0}, "boundary":)")).find("krylov_max_iterations"),
            std::string::npos);
}

TEST(Scenes, BuiltInScenesAreValid) {
  const std::filesystem::path dir = std::filesystem::path(HOFEM_SOURCE_DIR) / "scripts" / "scenes";
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".json") continue;
    EXPECT_NO_THROW({
      const Scene s = read_scene(entry.path().string());
      if (s.mesh.file.empty()) build_scene_mesh(s);
      if (s.embedded && s.embedded->shape.file.empty()) build_embedded_mesh(s);
    }) << entry.path();
    ++count;
  }
  EXPECT_GE(count, 10);
}

// The tube generator: volume pi (r_out^2 - r_in^2) h (P2: curved elements, so
// the volume converges at the geometry's order; P1 chords lose O(h^2)), no
// seam duplicates, and every element positively oriented.
TEST(Scenes, HollowCylinderMesh) {
  const double exact = M_PI * (1.0 - 0.25) * 2.0;
  for (int order : {1, 2}) {
    const Mesh m = hollow_cylinder_mesh(0.5, 1.0, 2.0, 2, 24, 4, CellType::Tetrahedron, order);
    const DofMap dofs(m.num_nodes(), {});
    const Assembler a(m, dofs);  // throws on an inverted element
    const double v = a.element_volumes().sum();
    // Chords of a 24-gon: relative area deficit 1 - sin(2 pi/24)/(2 pi/24) = 1.1e-2;
    // quadratic arcs are ~1e-5 off.
    EXPECT_NEAR(v, exact, (order == 1 ? 1.2e-2 : 1e-4) * exact) << order;
    EXPECT_FALSE(m.node_set("inner").empty());
    EXPECT_FALSE(m.node_set("top").empty());
  }
  // Straight-sided (curved = false): the P2 tube is the P1 tube's chords, so its
  // volume is the P1 volume to rounding (1e-12: sums of ~200 element volumes),
  // with the same nodes and node sets as the curved P2 tube (only moved).
  for (const CellType cell : {CellType::Tetrahedron, CellType::Hexahedron}) {
    const Mesh p1 = hollow_cylinder_mesh(0.5, 1.0, 2.0, 2, 24, 4, cell, 1);
    const Mesh straight = hollow_cylinder_mesh(0.5, 1.0, 2.0, 2, 24, 4, cell, 2, false);
    const Mesh curved = hollow_cylinder_mesh(0.5, 1.0, 2.0, 2, 24, 4, cell, 2);
    auto volume = [](const Mesh& m) {
      const DofMap dofs(m.num_nodes(), {});
      return Assembler(m, dofs).element_volumes().sum();
    };
    EXPECT_NEAR(volume(straight), volume(p1), 1e-12 * exact);
    EXPECT_GT(volume(curved) - volume(straight), 1e-3 * exact);  // the 24-gon's 1.1e-2 deficit, recovered
    EXPECT_EQ(straight.num_nodes(), curved.num_nodes());
    for (const char* set : {"inner", "outer", "bottom", "top", "boundary"})
      EXPECT_EQ(straight.node_set(set).size(), curved.node_set(set).size()) << set;
  }
  // The seam is merged: no two nodes coincide (Hex20 has the most seam nodes).
  const Mesh hex = hollow_cylinder_mesh(0.5, 1.0, 2.0, 1, 8, 1, CellType::Hexahedron, 2);
  double closest = 1e300;
  for (int i = 0; i < hex.num_nodes(); ++i)
    for (int j = i + 1; j < hex.num_nodes(); ++j) closest = std::min(closest, (hex.nodes.col(i) - hex.nodes.col(j)).norm());
  EXPECT_GT(closest, 0.1);
  const DofMap dofs(hex.num_nodes(), {});
  EXPECT_NO_THROW(Assembler(hex, dofs));
}

std::string temp_dir(const std::string& name) {
  const auto d = std::filesystem::temp_directory_path() / ("hofem_test_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  return d.string();
}

// An explicit run with a floor: frames every 2 steps plus the last, a .pvd with
// their times, stats.json with a row per step; no Hessian, no consistent mass,
// no linear solver; the floor is evaluated.
TEST(Scenes, ExplicitRunWritesFramesAndBuildsNoHessian) {
  Scene s = parse_scene(R"({
    "name": "drop",
    "mesh": {"box": {"min": [0, 0, 0.01], "max": [1, 1, 1.01], "cells": [2, 2, 2]}},
    "material": {"model": "neohookean", "young": 1e4, "poisson": 0.3, "density": 100},
    "integrator": "leapfrog", "dt": 0.002, "duration": 0.1,
    "gravity": [0, 0, -9.81], "floor": {"height": 0, "stiffness": 1e4},
    "output": {"every": 20}})",
                        "drop.json");
  const std::string dir = temp_dir("explicit");
  const SceneRunResult r = run_scene(s, dir);
  ASSERT_TRUE(r.ok) << r.message;
  const auto& st = r.stats;
  EXPECT_EQ(st["steps"].size(), 50u);
  EXPECT_EQ(st["frames"].get<int>(), 4);  // steps 0, 20, 40, 50
  EXPECT_EQ(st["built"]["hessian_assemblies"].get<int>(), 0);
  EXPECT_EQ(st["built"]["mass_matrices_built"].get<int>(), 0);
  EXPECT_EQ(st["built"]["symbolic_analyses"].get<int>(), 0);
  EXPECT_EQ(st["built"]["mass"].get<std::string>(), "lumped (row-sum)");
  EXPECT_GT(st["built"]["floor_evaluations"].get<int>(), 0);
  EXPECT_GT(st["built"]["contact_node_steps"].get<int>(), 0) << "the body must reach the floor";
  EXPECT_TRUE(std::filesystem::exists(dir + "/drop.pvd"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/frame_00050.vtu"));
  std::ifstream pvd(dir + "/drop.pvd");
  const std::string text((std::istreambuf_iterator<char>(pvd)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("timestep=\"0.1"), std::string::npos) << text;
  nlohmann::json file;
  std::ifstream(dir + "/stats.json") >> file;
  EXPECT_EQ(file["steps"].size(), 50u);
  EXPECT_TRUE(file["steps"][0].contains("energy"));
  std::filesystem::remove_all(dir);
}

// A fixed Krylov budget (solver.krylov_iterations): the semi-implicit step
// solves once per step, so the run does exactly steps x k iterations; min det
// F is recorded per step and over the run (a falling cube stays near 1: no
// element inverts).
TEST(Scenes, FixedKrylovBudgetAndVolumeRatioAreRecorded) {
  Scene s = parse_scene(R"({
    "name": "budget",
    "mesh": {"box": {"min": [0, 0, 0.5], "max": [1, 1, 1.5], "cells": [2, 2, 2]}},
    "material": {"model": "neohookean", "young": 1e4, "poisson": 0.3, "density": 100},
    "integrator": "semi-implicit", "dt": 0.01, "duration": 0.1,
    "gravity": [0, 0, -9.81], "solver": {"linear": "cr+jacobi", "krylov_iterations": 3}})",
                        "budget.json");
  SceneRunOptions o;
  o.write_frames = false;
  const SceneRunResult r = run_scene(s, "", o);
  ASSERT_TRUE(r.ok) << r.message;
  const auto& st = r.stats;
  ASSERT_EQ(st["steps"].size(), 10u);
  EXPECT_EQ(st["built"]["linear_iterations"].get<int>(), 10 * 3);
  for (const auto& row : st["steps"]) {
    EXPECT_EQ(row["linear_iterations"].get<int>(), 3);
    EXPECT_GT(row["min_det_F"].get<double>(), 0.9);
    EXPECT_EQ(row["inverted_elements"].get<int>(), 0);
  }
  EXPECT_EQ(st["deformation"]["max_inverted_elements"].get<int>(), 0);
  EXPECT_GT(st["deformation"]["min_det_F"].get<double>(), 0.9);
  // A static scene has no steps to budget.
  try {
    parse_scene(R"({"name": "s", "mesh": {"box": {"min": [0, 0, 0], "max": [1, 1, 1], "cells": [1, 1, 1]}},
      "material": {"model": "neohookean", "young": 1e4, "poisson": 0.3}, "integrator": "static",
      "solver": {"linear": "cg+jacobi", "krylov_iterations": 3}})",
                "static.json");
    ADD_FAILURE() << "a static scene with krylov_iterations was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("static.json: solver.krylov_iterations is for time-stepping scenes"),
              std::string::npos)
        << e.what();
  }
}

// A scene's solver is one SolverSpec: the serial choice, the Krylov budget and
// hypre's options for distributed runs (which `hofem mms` takes as flags) all
// come from the "solver" object; a bad distributed option names its key.
TEST(Scenes, SolverObjectSetsEverySolverOption) {
  const std::string head = R"({"name": "s", "mesh": {"box": {"min": [0, 0, 0], "max": [1, 1, 1], "cells": [1, 1, 1]}},
      "material": {"model": "neohookean", "young": 1e4, "poisson": 0.3}, "integrator": "implicit-euler",
      "dt": 0.01, "duration": 0.01, "solver": )";
  const Scene s = parse_scene(head + R"({"linear": "gmres+ic0", "krylov_iterations": 7,
      "distributed": {"krylov": "gmres", "amg": "amg-nodal", "rigid_body_modes": true, "gmres_restart": 30}}})",
                              "solver.json");
  const SolverSpec& spec = s.dynamics.solver;
  EXPECT_EQ(spec.method, SolverMethod::Gmres);
  EXPECT_EQ(spec.preconditioner, "ic0");
  EXPECT_EQ(spec.name(), "gmres+ic0");
  EXPECT_EQ(spec.fixed_iterations, 7);
  EXPECT_EQ(spec.distributed.krylov, "gmres");
  EXPECT_EQ(spec.distributed.amg, "amg-nodal");
  EXPECT_TRUE(spec.distributed.rigid_body_modes);
  EXPECT_EQ(spec.distributed.gmres_restart, 30);
  EXPECT_TRUE(parse_scene(head + "{}}", "default.json").dynamics.solver.is_auto());
  for (const auto& [bad, key] : std::vector<std::pair<std::string, std::string>>{
           {R"({"distributed": {"amg": "fast"}})", "solver.distributed.amg"},
           {R"({"distributed": {"krylov": "bicgstab"}})", "solver.distributed.krylov"},
           {R"({"distributed": {"gmres_restart": 0}})", "solver.distributed.gmres_restart"},
           {R"({"distributed": {"coarsening": "hmis"}})", "coarsening"}}) {
    try {
      parse_scene(head + bad + "}", "bad.json");
      ADD_FAILURE() << bad << " was accepted";
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find("bad.json: "), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  }
}

// Implicit without a floor: one symbolic analysis for the whole run, no floor
// work; a static scene builds no mass at all.
TEST(Scenes, ImplicitAndStaticRunsBuildOnlyWhatTheyNeed) {
  // (Without a load nothing moves and Newton stops before factorising at all.)
  Scene s = parse_scene(with("\"boundary\"", "\"gravity\": [0, 0, -9.81], \"boundary\""), "implicit.json");
  s.name = "implicit";
  const std::string dir = temp_dir("implicit");
  SceneRunOptions o;
  o.write_frames = false;
  SceneRunResult r = run_scene(s, dir, o);
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_EQ(r.stats["built"]["symbolic_analyses"].get<int>(), 1);
  EXPECT_EQ(r.stats["built"]["floor_evaluations"].get<int>(), 0);
  // One, once: the nodal mass matrix over all nodes serves Newton's matrix, the
  // kinetic energy and the coupling to prescribed nodes.
  EXPECT_EQ(r.stats["built"]["mass_matrices_built"].get<int>(), 1);
  EXPECT_EQ(r.stats["built"]["polar_decompositions"].get<long long>(), 0);  // Neo-Hookean needs none
  // Corotated computes one per quadrature point and evaluation.
  Scene c = s;
  c.material = "corotated";
  const SceneRunResult rc = run_scene(c, dir, o);
  ASSERT_TRUE(rc.ok) << rc.message;
  EXPECT_GT(rc.stats["built"]["polar_decompositions"].get<long long>(), 0);

  Scene st = parse_scene(with("\"implicit-euler\", \"dt\": 0.01, \"duration\": 0.03", "\"static\", \"gravity\": [0, 0, -9.81]"),
                         "static.json");
  r = run_scene(st, dir, o);
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_EQ(r.stats["built"]["mass_matrices_built"].get<int>(), 0);
  EXPECT_EQ(r.stats["built"]["mass"].get<std::string>(), "none (static)");
  std::filesystem::remove_all(dir);
}

// ---------------------------------------------------------------------------
// Embedded (finite cell) scenes.

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The tuples of a named Float64 DataArray of an ASCII .vtu written by write_vtu.
Eigen::Matrix3Xd vtu_vectors(const std::string& text, const std::string& name) {
  const size_t at = text.find("Name=\"" + name + "\"");
  if (at == std::string::npos) throw std::runtime_error("no DataArray " + name);
  const size_t begin = text.find('>', at) + 1, end = text.find("</DataArray>", begin);
  std::istringstream in(text.substr(begin, end - begin));
  std::vector<double> v;
  for (double x; in >> x;) v.push_back(x);
  return Eigen::Map<const Eigen::Matrix3Xd>(v.data(), 3, static_cast<Eigen::Index>(v.size() / 3));
}

// "/frame_0000k_surface.vtu", the embedded surface's frame k.
std::string fmt_frame(int k) { return "/frame_0000" + std::to_string(k) + "_surface.vtu"; }

const std::string kEmbeddedTiny =
    (std::filesystem::path(HOFEM_SOURCE_DIR) / "verification/unit/data/scene_embedded_tiny.json").string();

// The tiny scene: a tube (r 0.2-0.45, 1 x 12 x 2 generator cells: 144 tets)
// in a 2 x 2 x 2 Hex8 grid over [-0.5, 0.5]^2 x [0, 1], bottom plane fixed, top
// plane pushed down at 0.5 m/s for 3 steps of 0.01 s.
// embedded.stiffness_degree reaches the cut cells' rules (Longva et al. 2020
// integrated Hex20 at degree 4 where hofem's default is 6; the study variant):
// at degree 2 the simplified rules keep at most C(2 + 3, 3) = 10 points per cell
// where the default degree 4 keeps up to 35 (checked above).
TEST(Scenes, EmbeddedStiffnessDegreeSetsTheCutCellRules) {
  const Scene s = read_scene(kEmbeddedTiny, {"embedded.stiffness_degree=2", "duration=0.01"});
  ASSERT_TRUE(s.embedded);
  EXPECT_EQ(s.embedded->stiffness_degree, 2);
  SceneRunOptions run;
  run.write_frames = false;
  const SceneRunResult r = run_scene(s, "", run);
  ASSERT_TRUE(r.ok) << r.message;
  const auto& q = r.stats.at("embedded")["quadrature"];
  EXPECT_EQ(q["stiffness_degree"].get<int>(), 2);
  EXPECT_LE(q["points_after"].get<long long>(), 8 * 10);
  EXPECT_GT(q["points_after"].get<long long>(), 0);
}

TEST(Scenes, EmbeddedRunWritesTheSurfaceAndQuadratureFigures) {
  const Scene s = read_scene(kEmbeddedTiny);
  ASSERT_TRUE(s.embedded);
  const std::string dir = temp_dir("embedded");
  const SceneRunResult r = run_scene(s, dir);
  ASSERT_TRUE(r.ok) << r.message;
  const nlohmann::json& e = r.stats.at("embedded");
  // Every octant of the grid holds a quarter of the tube's half (volume fraction
  // ~0.5: far from full and from a sliver), so all 8 are cut and stabilised.
  EXPECT_EQ(e["cells"]["cut"].get<int>(), 8);
  EXPECT_EQ(e["cells"]["uncut"].get<int>(), 0);
  EXPECT_EQ(e["cells"]["empty"].get<int>(), 0);
  EXPECT_EQ(e["cells"]["dropped"].get<int>(), 0);
  EXPECT_EQ(e["cells"]["stabilised"].get<int>(), 8);
  // Simplification keeps at most C(4 + 3, 3) = 35 points of the degree-4 rule
  // per cell, out of a clipped rule of several points per tet piece (18 tets per cell).
  const auto& q = e["quadrature"];
  EXPECT_EQ(q["stiffness_degree"].get<int>(), 4);
  EXPECT_LE(q["points_after"].get<long long>(), 8 * 35);
  EXPECT_LT(q["points_after"].get<long long>(), q["points_before"].get<long long>());
  EXPECT_EQ(q["simplification_failures"].get<int>(), 0);
  EXPECT_GT(q["generation_seconds"].get<double>(), 0.0);
  // The clipped rules integrate 1 exactly: the cells hold the tube's volume up to rounding.
  EXPECT_NEAR(e["geometry"]["volume_in_cells"].get<double>(), e["geometry"]["volume"].get<double>(),
              1e-12 * e["geometry"]["volume"].get<double>());
  EXPECT_EQ(e["surface_vertices_extrapolated"].get<int>(), 0);
  // Surface of the tube mesh: inner and outer walls 2 x (12 x 2) triangles each,
  // the end annuli 2 x 12 each; every vertex (2 radii x 12 x 3 levels) is on it.
  EXPECT_EQ(e["geometry"]["surface_triangles"].get<int>(), 144);
  EXPECT_EQ(e["geometry"]["surface_vertices"].get<int>(), 72);
  for (int k = 0; k <= 3; ++k)
    EXPECT_TRUE(std::filesystem::exists(dir + fmt_frame(k))) << k;
  EXPECT_TRUE(std::filesystem::exists(dir + "/embedded-tiny_surface.pvd"));
  const std::string vtu = read_text(dir + fmt_frame(3));
  EXPECT_NE(vtu.find("NumberOfPoints=\"72\" NumberOfCells=\"144\""), std::string::npos);
  // The ends of the tube lie on the grid's end planes, where the prescribed
  // nodes alone interpolate: a fixed plane gives 0 and a translated one exactly
  // the translation (bilinear interpolation reproduces constants), whatever the
  // interior does. At t = 0.03 the top has moved by 0.5 * 0.03 = 0.015 down.
  const Eigen::Matrix3Xd X = vtu_vectors(vtu, "Points"), u = vtu_vectors(vtu, "displacement");
  ASSERT_EQ(X.cols(), 72);
  ASSERT_EQ(u.cols(), 72);
  int ends = 0;
  for (int i = 0; i < 72; ++i) {
    if (X(2, i) == 0.0 || X(2, i) == 1.0) ++ends;
    if (X(2, i) == 0.0) {
      EXPECT_LT(u.col(i).norm(), 1e-14) << i;
    } else if (X(2, i) == 1.0) {
      EXPECT_LT((u.col(i) - Eigen::Vector3d(0, 0, -0.015)).norm(), 1e-14) << i;
    } else {
      // The middle level (z = 0.5) is free: compressed between the ends it moves
      // down less than the top (-0.003 here: the wave has not crossed the tube,
      // c = sqrt(E / rho) = 10 m/s) and bulges outwards (Poisson effect; ~1e-3).
      EXPECT_GT(u(2, i), -0.015) << i;
      EXPECT_LT(u(2, i), 0.0) << i;
      EXPECT_GT(u(0, i) * X(0, i) + u(1, i) * X(1, i), 0.0) << i;
    }
  }
  EXPECT_EQ(ends, 48);
  std::filesystem::remove_all(dir);
}

// The surface follows the background exactly for fields the background
// reproduces: an affine displacement is interpolated to rounding (1e-14 for
// unit-sized coordinates); without simplification the points stay as clipped.
TEST(Scenes, EmbeddedSurfaceFollowsTheBackground) {
  Scene s = read_scene(kEmbeddedTiny);
  const Mesh background = build_scene_mesh(s);
  const SceneEmbedding embedding(s, background);
  Eigen::Matrix3d A;
  A << 0.1, -0.2, 0.05, 0.3, 0.0, -0.1, 0.02, 0.04, -0.3;
  const Eigen::Vector3d b(0.01, -0.02, 0.03);
  const Eigen::Matrix3Xd u_nodes = (A * background.nodes).colwise() + b;
  const Eigen::VectorXd u = u_nodes.reshaped();
  const Eigen::Matrix3Xd expected = (A * embedding.surface().nodes).colwise() + b;
  EXPECT_LT((embedding.surface_displacement(u) - expected).cwiseAbs().maxCoeff(), 1e-14);

  s.embedded->simplify = false;
  const SceneEmbedding raw(s, background);
  EXPECT_EQ(raw.stats()["quadrature"]["points_after"], raw.stats()["quadrature"]["points_before"]);
  EXPECT_EQ(raw.stats()["quadrature"]["points_before"], embedding.stats()["quadrature"]["points_before"]);
}

// What a stored finite-cell run is measured with (embedded_geometry: no rules)
// must be what the run had: the same surface and the same active cells. The
// grid is made 5 x 5 over [-0.7, 0.7]^2 so that it has cells the tube misses
// (the centre, the corners), cut cells, and - with drop_fraction set between the
// smallest and largest cut fraction - dropped cells; "active" is checked against
// the rules themselves (null: uncut, empty: missed or dropped).
TEST(Scenes, EmbeddedGeometryIsTheRunsSurfaceAndActiveCells) {
  const SceneOverrides grid = {"mesh.box.min=[-0.7, -0.7, 0]", "mesh.box.max=[0.7, 0.7, 1]", "mesh.box.cells=[5, 5, 2]"};
  const Scene probe = read_scene(kEmbeddedTiny, grid);
  const Mesh background = build_scene_mesh(probe);
  const std::vector<double> f =
      finite_cell_volume_fractions(background, mesh_tetrahedra(build_embedded_mesh(probe)), FiniteCellOptions{});
  double lo = 1.0, hi = 0.0;
  for (double x : f)
    if (x > 0.0 && x < 1.0) lo = std::min(lo, x), hi = std::max(hi, x);
  ASSERT_LT(lo, hi) << "the grid should have cut cells of different fractions";
  SceneOverrides overrides = grid;
  overrides.push_back(fmt::format("embedded.drop_fraction={:.17g}", 0.5 * (lo + hi)));
  const Scene s = read_scene(kEmbeddedTiny, overrides);
  const SceneEmbedding embedding(s, background);
  const EmbeddedGeometry g = embedded_geometry(s, background);
  const ElementRules rules = embedding.element_rules();
  int missed = 0, dropped = 0, kept = 0;
  for (int e = 0; e < background.num_elements(); ++e) {
    const bool integrates = !rules.stiffness[e] || rules.stiffness[e]->rule.size() > 0;
    EXPECT_EQ(bool(g.active[e]), integrates) << "element " << e << ", volume fraction " << f[e];
    EXPECT_EQ(bool(embedding.active_cells()[e]), integrates) << "element " << e;
    missed += f[e] == 0.0;
    dropped += f[e] > 0.0 && !integrates;
    kept += integrates;
  }
  EXPECT_GT(missed, 0);
  EXPECT_GT(dropped, 0);
  EXPECT_GT(kept, 0);
  EXPECT_EQ(g.surface.elements, embedding.surface().elements);
  EXPECT_EQ(g.surface.nodes, embedding.surface().nodes);
}

// The tiny scene under gravity in a wider grid, [-1, 1]^2 x [0, 1] in 4 x 4 x 2
// cells, static and dynamic: the outer ring of cells (every point at r >= 0.5 >
// r_out) holds no material, so its free nodes carry no stiffness or mass and stay
// exactly at rest - without the finite-cell rules the whole box would sag.
TEST(Scenes, StaticAndDynamicEmbeddedRunsUseTheFiniteCellRules) {
  const std::string base = read_text(kEmbeddedTiny);
  for (const bool is_static : {true, false}) {
    std::string text = base;
    auto replace = [&](const std::string& from, const std::string& to) {
      const size_t at = text.find(from);
      if (at == std::string::npos) throw std::logic_error("tiny scene lacks '" + from + "'");
      text.replace(at, from.size(), to);
    };
    replace(R"("dt": 0.01, "duration": 0.03,)", R"("dt": 0.01, "duration": 0.03, "gravity": [0, 0, -9.81],)");
    if (is_static) replace(R"("implicit-euler", "dt": 0.01, "duration": 0.03,)", R"("static",)");
    replace(R"("min": [-0.5, -0.5, 0], "max": [0.5, 0.5, 1], "cells": [2, 2, 2])",
            R"("min": [-1, -1, 0], "max": [1, 1, 1], "cells": [4, 4, 2])");
    replace(R"("velocity": [0, 0, -0.5]})", R"("velocity": [0, 0, -0.5], "until": 0.03})");
    const Scene s = parse_scene(text, "wide.json");
    const std::string dir = temp_dir("wide_embedded");
    const SceneRunResult r = run_scene(s, dir);
    ASSERT_TRUE(r.ok) << r.message;
    EXPECT_EQ(r.stats["embedded"]["cells"]["empty"].get<int>(), 24);
    EXPECT_EQ(r.stats["embedded"]["cells"]["cut"].get<int>(), 8);
    const int last = is_static ? 0 : 3;
    const std::string background = read_text(dir + "/frame_0000" + std::to_string(last) + ".vtu");
    const Eigen::Matrix3Xd X = vtu_vectors(background, "Points"), u = vtu_vectors(background, "displacement");
    ASSERT_EQ(X.cols(), 5 * 5 * 3);
    // Largest displacement of the free level's (z = 0.5) nodes off / on the material's cells.
    double outer = 0.0, inner = 0.0;
    for (int i = 0; i < X.cols(); ++i) {
      if (X(2, i) != 0.5) continue;
      const bool ring = std::max(std::abs(X(0, i)), std::abs(X(1, i))) > 0.75;
      (ring ? outer : inner) = std::max(ring ? outer : inner, u.col(i).norm());
    }
    EXPECT_EQ(outer, 0.0) << is_static;
    // Static: gravity sags the tube on the ~rho g L^2 / E = 0.1 m scale; dynamic:
    // it falls g t^2 / 2 = 4.4e-3 m in 0.03 s where nothing holds it.
    EXPECT_GT(inner, 1e-3) << is_static;
    // The top of the tube is at its prescribed place in the last surface frame.
    const std::string surface = read_text(dir + fmt_frame(last));
    const Eigen::Matrix3Xd Xs = vtu_vectors(surface, "Points"), us = vtu_vectors(surface, "displacement");
    for (int i = 0; i < Xs.cols(); ++i) {
      if (Xs(2, i) == 1.0) {
        EXPECT_LT((us.col(i) - Eigen::Vector3d(0, 0, -0.015)).norm(), 1e-14) << i;
      }
    }
    std::filesystem::remove_all(dir);
  }
}

TEST(Scenes, InvalidEmbeddedInputNamesTheKey) {
  const std::string base = read_text(kEmbeddedTiny);
  auto edit = [&](const std::string& from, const std::string& to) {
    std::string t = base;
    const size_t at = t.find(from);
    if (at == std::string::npos) throw std::logic_error("tiny scene lacks '" + from + "'");
    return t.replace(at, from.size(), to);
  };
  const std::string tube = R"("tube": {"r_in": 0.2, "r_out": 0.45, "height": 1.0, "cells": [1, 12, 2]})";
  struct Case {
    std::string text, expected;
  };
  const Case cases[] = {
      {edit(tube, tube + R"(, "stabilization": 1e-6)"),
       "t.json: key 'embedded.stabilization' is unknown (valid: box, drop_fraction, file, simplify, stabilisation, "
       "stiffness_degree, torus, tube)"},
      {edit(tube, tube + R"(, "stiffness_degree": 0)"), "t.json: embedded.stiffness_degree = 0 is out of range [1, 20]"},
      {edit(tube, tube + R"(, "stabilisation": -1e-6)"),
       "t.json: embedded.stabilisation = -1e-06 is out of range [0, 1]"},
      {edit(tube, tube + R"(, "drop_fraction": 1)"), "t.json: embedded.drop_fraction = 1 is out of range [0, 1)"},
      {edit(tube, tube + R"(, "simplify": "yes")"), "t.json: embedded.simplify must be true or false"},
      {edit(tube, tube + R"(, "file": "a.msh")"), "t.json: embedded needs exactly one of 'box', 'tube', 'torus' and 'file'"},
      {edit("\"r_in\": 0.2", "\"r_in\": -0.2"), "t.json: embedded.tube.r_in = -0.2 is out of range (0,"},
      {edit(R"("box": {"min": [-0.5, -0.5, 0], "max": [0.5, 0.5, 1], "cells": [2, 2, 2]})",
            R"("tube": {"r_in": 0.5, "r_out": 1, "height": 1, "cells": [1, 8, 1]})"),
       "t.json: mesh.tube cannot be the background of an embedded scene"},
  };
  for (const Case& c : cases) {
    const std::string e = error_of(c.text);
    EXPECT_NE(e.find(c.expected), std::string::npos) << "expected: " << c.expected << "\n     got: " << e;
  }
  // Geometry files are checked when the run builds them, with the key that names them.
  auto build_error = [&](const std::string& text) {
    try {
      const Scene s = parse_scene(text, "t.json");
      const Mesh background = build_scene_mesh(s);
      SceneEmbedding embedding(s, background);
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  std::string e = build_error(edit(tube, R"("file": "/nonexistent/geometry.msh")"));
  EXPECT_NE(e.find("t.json: embedded.file: "), std::string::npos) << e;
  EXPECT_NE(e.find("/nonexistent/geometry.msh"), std::string::npos) << e;
  const std::string hexes =
      (std::filesystem::path(HOFEM_SOURCE_DIR) / "verification/unit/data/gmsh_hex8_v41.msh").string();
  e = build_error(edit(tube, "\"file\": \"" + hexes + "\""));
  EXPECT_NE(e.find("t.json: embedded.file: '" + hexes + "' is not a tetrahedral mesh"), std::string::npos) << e;
  // A tube taller than the grid: a third of it would silently vanish.
  e = build_error(edit("\"height\": 1.0", "\"height\": 1.5"));
  EXPECT_NE(e.find("t.json: embedded: 33.3 % of the geometry's volume lies outside the background mesh"),
            std::string::npos)
      << e;
}

}  // namespace
}  // namespace hofem
