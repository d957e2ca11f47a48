// Scene files: every key validated before work starts (errors name the file and
// the key, with the valid choices), the built-in scenes parse, and a run writes
// its frames, .pvd and stats.json while building only what the scene needs.
#include "assembly/assembler.hpp"
#include "mesh/tube_mesh.hpp"
#include "mesh/vtu_writer.hpp"
#include "scene/scene.hpp"
#include "scene/scene_runner.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
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
      {with("\"integrator\"", "\"integrater\""), "t.json: key 'integrater' is unknown (valid: boundary, damping, dt,"},
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
      {with("\"mesh\": {", "\"mesh\": {\"file\": \"a.msh\", "), "t.json: mesh needs exactly one of 'box', 'tube' and 'file'"},
      {with("\"motion\": \"fixed\"", "\"motion\": \"glued\""), "t.json: boundary[0].motion = 'glued' is not one of: fixed"},
      {with("\"motion\": \"fixed\"", "\"motion\": {\"rotate\": {\"point\": [0,0,0], \"axis\": [0,0,0], \"omega\": 1}}"),
       "t.json: boundary[0].motion.rotate.axis must be a non-zero vector"},
      {with("\"boundary\"", "\"solver\": {\"linear\": \"magic\"}, \"boundary\""),
       "t.json: solver.linear = 'magic' is not one of: cholmod,"},
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

TEST(Scenes, BuiltInScenesAreValid) {
  const std::filesystem::path dir = std::filesystem::path(HOFEM_SOURCE_DIR) / "scripts" / "scenes";
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".json") continue;
    EXPECT_NO_THROW({
      const Scene s = read_scene(entry.path().string());
      if (s.mesh_file.empty()) build_scene_mesh(s);
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

}  // namespace
}  // namespace hofem
