// Bad input is refused with its source named: special files before a byte is
// read, caps before anything is allocated, a 10^5-deep JSON before it is
// parsed, a number overflow with its key, an inverted element with its file,
// line and tag. Every case feeds a real file (data/bad_*, or one made here).
#include "io/gmsh_reader.hpp"
#include "io/input_file.hpp"
#include "mesh/mesh_quality.hpp"
#include "mesh/mesh_reorient.hpp"
#include "mesh/box_mesh.hpp"
#include "scene/scene.hpp"
#include "scene/scene_mesh.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <sys/stat.h>
#include <unistd.h>

namespace hofem {
namespace {

namespace fs = std::filesystem;
const std::string kData = HOFEM_TEST_DATA_DIR;

// The message of the exception `f` throws (as E), or a failure.
template <class E, class F>
std::string message_of(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  ADD_FAILURE() << "no exception";
  return {};
}

// A scratch directory for files made by a test, removed afterwards.
struct Scratch {
  fs::path dir = fs::temp_directory_path() / ("hofem_input_" + std::to_string(::getpid()));
  Scratch() { fs::create_directories(dir); }
  ~Scratch() { fs::remove_all(dir); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(dir / name) << text;
    return (dir / name).string();
  }
};

// Restores the process-wide caps a test changes.
struct LimitsGuard {
  InputLimits saved = input_limits();
  ~LimitsGuard() { input_limits() = saved; }
};

TEST(InputFile, CharacterDeviceIsRefusedBeforeReading) {
  // Refused by its kind, not read up to the size cap (that would end in "over the
  // cap" after 2 GiB of zeros; a hang without a cap).
  const std::string m = message_of<MeshError>([] { read_gmsh("/dev/zero"); });
  EXPECT_NE(m.find("/dev/zero: cannot read the mesh file: it is a character device"), std::string::npos) << m;
}

TEST(InputFile, SceneWhoseMeshIsACharacterDeviceNamesSceneKeyAndDevice) {
  const Scene s = read_scene(kData + "/bad_scene_dev_zero.json");
  const std::string m = message_of<SceneError>([&] { build_scene_mesh(s); });
  EXPECT_NE(m.find("bad_scene_dev_zero.json: mesh.file: /dev/zero: cannot read the mesh file: it is a character device"),
            std::string::npos)
      << m;
}

TEST(InputFile, FifoIsRefusedWithoutWaitingForAWriter) {
  Scratch scratch;
  const std::string fifo = (scratch.dir / "pipe.msh").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  // Opening a FIFO for reading blocks until a writer comes: the test would hang
  // (until ctest's timeout) if the reader opened it.
  std::string m = message_of<MeshError>([&] { read_gmsh(fifo); });
  EXPECT_NE(m.find("pipe.msh: cannot read the mesh file: it is a FIFO (named pipe)"), std::string::npos) << m;
  m = message_of<SceneError>([&] { read_scene(fifo); });
  EXPECT_NE(m.find("pipe.msh: cannot read the scene file: it is a FIFO"), std::string::npos) << m;
}

TEST(InputFile, DirectoryAndMissingFileAreNamed) {
  std::string m = message_of<SceneError>([] { read_scene(kData); });
  EXPECT_NE(m.find("cannot read the scene file: it is a directory"), std::string::npos) << m;
  m = message_of<MeshError>([] { read_gmsh("/nonexistent/x.msh"); });
  EXPECT_NE(m.find("/nonexistent/x.msh: cannot open the mesh file: No such file or directory"), std::string::npos) << m;
}

TEST(InputFile, FileOverTheSizeCapIsRefusedBeforeReading) {
  LimitsGuard guard;
  set_input_limit("mesh-file-mb=1");
  Scratch scratch;
  const std::string big = scratch.write("big.msh", std::string(1100 * 1024, ' '));
  const std::string m = message_of<MeshError>([&] { read_gmsh(big); });
  EXPECT_NE(m.find("big.msh: the mesh file is 1126400 bytes, over the cap of 1048576 bytes"), std::string::npos) << m;
}

TEST(InputFile, LimitsAreSetByNameAndBadOnesNamed) {
  InputLimits l;
  set_input_limit("elements=5e7", l);
  EXPECT_EQ(l.elements, 50'000'000);
  set_input_limit("scene-file-kb=2", l);
  EXPECT_EQ(l.scene_file_bytes, 2048u);
  std::string m = message_of<std::invalid_argument>([&] { set_input_limit("frobs=3", l); });
  EXPECT_NE(m.find("unknown cap 'frobs' (valid: mesh-file-mb, scene-file-kb, elements, nodes, order, json-depth, "
                   "boundary-entries"),
            std::string::npos)
      << m;
  for (const char* bad : {"elements=", "elements=-4", "elements=2.5", "elements=1e400", "elements=abc"})
    EXPECT_THROW(set_input_limit(bad, l), std::invalid_argument) << bad;
}

TEST(SceneInput, DeeplyNestedJsonIsRefusedWithTheLine) {
  Scratch scratch;
  // 10^5 levels, 200 KB: under the size cap, so the depth cap must catch it
  // (without it, this input crashed the parser's consumers with a stack overflow).
  const std::string text = "{\"name\": \"deep\",\n \"mesh\": " + std::string(100000, '[') + std::string(100000, ']') + "}";
  const std::string path = scratch.write("deep.json", text);
  const std::string m = message_of<SceneError>([&] { read_scene(path); });
  EXPECT_NE(m.find("deep.json: line 2: JSON nested deeper than 32 levels"), std::string::npos) << m;
  // Brackets inside strings are text, not nesting.
  const std::string quoted = "{\"name\": \"" + std::string(1000, '[') + "\"}";
  const std::string q = message_of<SceneError>([&] { parse_scene(quoted, "quoted.json"); });
  EXPECT_EQ(q.find("nested"), std::string::npos) << q;
}

TEST(SceneInput, NumberOverflowNamesFileAndKey) {
  const std::string m = message_of<SceneError>([] { read_scene(kData + "/bad_scene_overflow.json"); });
  EXPECT_NE(m.find("bad_scene_overflow.json: material.young: a number out of the range of a double"),
            std::string::npos)
      << m;
  // Inside an array, the element's index is named.
  const std::string a = message_of<SceneError>([] { parse_scene(R"({"gravity": [0, 1e999, 0]})", "g.json"); });
  EXPECT_NE(a.find("g.json: gravity[1]: a number out of the range"), std::string::npos) << a;
}

TEST(SceneInput, NulBytesAndDuplicateKeysAreRefused) {
  // nlohmann's parser would stop at the NUL and ignore the rest of the file.
  const std::string nul = std::string("{\"name\": \"a\"}\n") + '\0' + "{\"garbage\": 1}";
  std::string m = message_of<SceneError>([&] { parse_scene(nul, "nul.json"); });
  EXPECT_NE(m.find("nul.json: line 2: a NUL byte"), std::string::npos) << m;
  // JSON allows a key twice (the last wins); a scene must not say two things.
  m = message_of<SceneError>([] { parse_scene(R"({"material": {"young": 1e5, "young": 1e9}})", "dup.json"); });
  EXPECT_NE(m.find("dup.json: material.young: the key appears twice in its object"), std::string::npos) << m;
}

TEST(SceneInput, HugeBoxIsRefusedBeforeAllocating) {
  // Refused while parsing (parse_scene builds no mesh), by the cap's message.
  const std::string m = message_of<SceneError>([] { read_scene(kData + "/bad_scene_box_1000.json"); });
  EXPECT_NE(m.find("bad_scene_box_1000.json: mesh.box.cells = [1000, 1000, 1000] (tet 1): 6000000000 elements exceed "
                   "the cap of 20000000 (raise it with --limit elements=N)"),
            std::string::npos)
      << m;
  // The cap is a cap: raised, the same file parses (the mesh is not built here).
  LimitsGuard guard;
  set_input_limit("elements=1e10");
  set_input_limit("nodes=1e10");
  EXPECT_NO_THROW(read_scene(kData + "/bad_scene_box_1000.json"));
}

TEST(SceneInput, OrderAndBoundaryEntriesHaveCaps) {
  std::string m = message_of<SceneError>([] {
    parse_scene(R"({"mesh": {"box": {"min": [0,0,0], "max": [1,1,1], "cells": [1,1,1]}, "order": 50}})", "o.json");
  });
  EXPECT_NE(m.find("o.json: mesh.order = 50 is out of range [1, 10]"), std::string::npos) << m;
  std::string entries;
  for (int i = 0; i < 10001; ++i) entries += std::string(i ? "," : "") + R"({"nodes": "xmin", "motion": "fixed"})";
  const std::string scene = R"({"mesh": {"box": {"min": [0,0,0], "max": [1,1,1], "cells": [1,1,1]}},
    "material": {"model": "neohookean", "young": 1e5, "poisson": 0.3}, "integrator": "static", "boundary": [)" +
                            entries + "]}";
  m = message_of<SceneError>([&] { parse_scene(scene, "b.json"); });
  EXPECT_NE(m.find("b.json: boundary has 10001 entries, over the cap of 10000"), std::string::npos) << m;
}

TEST(SceneOverrides, ValuesAreAppliedThenValidatedLikeTheFile) {
  const std::string tiny = kData + "/scene_tiny.json";
  // JSON values, bare words as strings, array elements by index.
  const Scene s = read_scene(tiny, {"mesh.order=2", "mesh.cell=hex", "gravity.2=-1.5", "material.young=2e5"});
  EXPECT_EQ(s.order, 2);
  EXPECT_EQ(s.cell, CellType::Hexahedron);
  EXPECT_EQ(s.dynamics.gravity.z(), -1.5);
  EXPECT_EQ(s.young, 2e5);
  // An overridden value is validated exactly like one in the file.
  std::string m = message_of<SceneError>([&] { read_scene(tiny, {"material.poisson=0.5"}); });
  EXPECT_NE(m.find("scene_tiny.json: material.poisson = 0.5 is out of range (-1, 0.5)"), std::string::npos) << m;
  m = message_of<SceneError>([&] { read_scene(tiny, {"material.youngs=1"}); });
  EXPECT_NE(m.find("key 'material.youngs' is unknown"), std::string::npos) << m;
  m = message_of<SceneError>([&] { read_scene(tiny, {"mesh.order=eight"}); });
  EXPECT_NE(m.find("mesh.order must be an integer (got \"eight\")"), std::string::npos) << m;
  // The error says which override set the bad value (the longest path that is the
  // key or a parent of it), and blames none for an error in a key none touched.
  EXPECT_NE(m.find("(the value comes from the override 'mesh.order=eight')"), std::string::npos) << m;
  m = message_of<SceneError>([&] { read_scene(tiny, {"mesh.order=2", "material.youngs=1"}); });
  EXPECT_NE(m.find("(the value comes from the override 'material.youngs=1')"), std::string::npos) << m;
  m = message_of<SceneError>([&] { read_scene(tiny, {"mesh={\"box\": {}}", "mesh.cell=hex"}); });
  EXPECT_NE(m.find("(the value comes from the override 'mesh={\"box\": {}}')"), std::string::npos) << m;
  m = message_of<SceneError>([&] { read_scene(tiny, {"dt=-1", "duration=0.2"}); });
  EXPECT_NE(m.find("(the value comes from the override 'dt=-1')"), std::string::npos) << m;
  m = message_of<SceneError>([&] { read_scene(tiny, {"material.young=3e5", "integrator=static"}); });
  EXPECT_EQ(m.find("the value comes from"), std::string::npos) << m;  // dt of the file "does not apply"
  // An override that makes an unknown key deeper than the key is still named, and an
  // array index set as ".1" is the message's "[1]".
  m = message_of<SceneError>([&] { read_scene(tiny, {"mesh.order=2", "mesh.boxx.min=1"}); });
  EXPECT_NE(m.find("key 'mesh.boxx' is unknown"), std::string::npos) << m;
  EXPECT_NE(m.find("(the value comes from the override 'mesh.boxx.min=1')"), std::string::npos) << m;
  m = message_of<SceneError>([&] { read_scene(tiny, {"mesh.box.cells.1=0"}); });
  EXPECT_NE(m.find("mesh.box.cells[1]"), std::string::npos) << m;
  EXPECT_NE(m.find("(the value comes from the override 'mesh.box.cells.1=0')"), std::string::npos) << m;
  // Errors found once the mesh is built name the override too: a boundary entry's
  // node set is checked against the mesh, not by the parser.
  const Scene bad_set =
      read_scene(tiny, {R"(boundary=[{"nodes": "zmin", "motion": "fixed"}])", "boundary.0.nodes=nowhere"});
  m = message_of<SceneError>([&] { boundary_nodes(bad_set, build_scene_mesh(bad_set), 0); });
  EXPECT_NE(m.find("boundary[0].nodes = 'nowhere' is not a node set of the mesh"), std::string::npos) << m;
  EXPECT_NE(m.find("(the value comes from the override 'boundary.0.nodes=nowhere')"), std::string::npos) << m;
  // Malformed overrides are named.
  m = message_of<SceneError>([&] { read_scene(tiny, {"mesh.order"}); });
  EXPECT_NE(m.find("override 'mesh.order' is not key.path=VALUE"), std::string::npos) << m;
  m = message_of<SceneError>([&] { read_scene(tiny, {"dt.x=1"}); });
  EXPECT_NE(m.find("override 'dt.x=1': dt.x is inside a value that is not an object"), std::string::npos) << m;
  m = message_of<SceneError>([&] { read_scene(tiny, {"gravity.3=0"}); });
  EXPECT_NE(m.find("gravity.3 is past the end of an array of 3"), std::string::npos) << m;
}

TEST(MeshInput, InvertedTet10NamesFileLineAndTag) {
  const Mesh mesh = read_gmsh(kData + "/bad_inverted_tet10.msh");
  const std::string m = message_of<MeshError>([&] { validate_mesh(mesh); });
  // Element 7 of the file (index 1), on line 35; negative everywhere: a numbering fault.
  EXPECT_NE(m.find("bad_inverted_tet10.msh:35: element 7: inverted (det J = "), std::string::npos) << m;
  EXPECT_NE(m.find("negative at every point"), std::string::npos) << m;
  EXPECT_NE(m.find("--reorient"), std::string::npos) << m;
}

TEST(MeshInput, SceneOnAnInvertedMeshNamesSceneAndMesh) {
  const Scene s = read_scene(kData + "/bad_scene_inverted_tet10.json");
  const std::string m = message_of<SceneError>([&] { build_scene_mesh(s); });
  EXPECT_NE(m.find("bad_scene_inverted_tet10.json: mesh: "), std::string::npos) << m;
  EXPECT_NE(m.find("bad_inverted_tet10.msh:35: element 7: inverted"), std::string::npos) << m;
  // --reorient flips it (with a warning) and the mesh validates.
  Scene fixed = s;
  fixed.reorient = true;
  EXPECT_NO_THROW(validate_mesh(build_scene_mesh(fixed)));
}

TEST(MeshInput, ReorientFlipsStraightInvertedElementsOnly) {
  Mesh mesh = read_gmsh(kData + "/bad_inverted_tet10.msh");
  const Eigen::VectorXi before = mesh.elements.col(1);
  EXPECT_EQ(reorient_inverted_elements(mesh), std::vector<int>{1});
  EXPECT_NO_THROW(validate_mesh(mesh));
  // The same nodes, renumbered: vertices 1 and 2 swap, and with them the edge nodes.
  Eigen::VectorXi a = before, b = mesh.elements.col(1);
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  EXPECT_EQ(a, b);
  EXPECT_EQ(mesh.elements(1, 1), before(2));
  EXPECT_EQ(mesh.elements(2, 1), before(1));

  // A folded element (det J of both signs) is not a numbering fault: untouched, still rejected.
  Mesh folded = read_gmsh(kData + "/bad_folded_tet10.msh");
  EXPECT_TRUE(reorient_inverted_elements(folded).empty());
  const std::string m = message_of<MeshError>([&] { validate_mesh(folded); });
  EXPECT_NE(m.find("bad_folded_tet10.msh:35: element 7: inverted"), std::string::npos) << m;
  EXPECT_NE(m.find("folds over itself"), std::string::npos) << m;
}

// Mirrored copies (z -> -z) of valid meshes of every element family are
// inverted everywhere; reorient must repair all of them (the mirror
// permutation must exist for face and interior nodes too).
TEST(MeshInput, ReorientRepairsMirroredMeshesOfEveryFamily) {
  for (const auto& [cell, order] : {std::pair{CellType::Tetrahedron, 1}, {CellType::Tetrahedron, 3},
                                    {CellType::Tetrahedron, 4}, {CellType::Hexahedron, 1}, {CellType::Hexahedron, 2}}) {
    Mesh m = box_mesh(unit_cube(2), cell, order);
    m.nodes.row(2) *= -1.0;
    EXPECT_THROW(validate_mesh(m), MeshError);
    EXPECT_EQ(static_cast<int>(reorient_inverted_elements(m).size()), m.num_elements());
    EXPECT_NO_THROW(validate_mesh(m)) << name(cell) << " order " << order;
  }
}

TEST(MeshInput, CoplanarAndRepeatedNodeElementsAreDegenerateWithTheirTags) {
  Scratch scratch;
  const std::string head = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n5\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n"
                           "5 0.3 0.3 0\n$EndNodes\n$Elements\n2\n1 4 0 1 2 3 4\n";
  // Element 9 on line 15: its fourth vertex (node 5) lies in the plane of the other three.
  Mesh mesh = read_gmsh(scratch.write("coplanar.msh", head + "9 4 0 1 2 3 5\n$EndElements\n"));
  std::string m = message_of<MeshError>([&] { validate_mesh(mesh); });
  EXPECT_NE(m.find("coplanar.msh:15: element 9: degenerate (det J = 0.000e+00"), std::string::npos) << m;
  // Element 9 repeats node 1.
  mesh = read_gmsh(scratch.write("repeated.msh", head + "9 4 0 1 2 3 1\n$EndElements\n"));
  m = message_of<MeshError>([&] { validate_mesh(mesh); });
  EXPECT_NE(m.find("repeated.msh:15: element 9: degenerate"), std::string::npos) << m;
}

}  // namespace
}  // namespace hofem
