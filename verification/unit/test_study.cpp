// The pieces of hofem study (core/study) on cases with known answers: point
// location in curved cells, surface lattices and body quadrature against exact
// areas and volumes, the field error of exactly representable fields, study
// files refused key by key, Richardson's estimate, and a study end to end.
#include "embedded/embedded_points.hpp"
#include "mesh/box_mesh.hpp"
#include "mesh/tube_mesh.hpp"
#include "study/recorded_run.hpp"
#include "study/scene_error.hpp"
#include "study/study.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <unistd.h>

namespace hofem {
namespace {

namespace fs = std::filesystem;

// Random points inside the elements of a mesh: x = X_e(xi) for random xi in
// the reference cell, with their element.
Eigen::Matrix3Xd points_inside(const Mesh& mesh, int count, std::vector<int>& element) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const ReferenceBasis& basis = lagrange_basis(mesh.cell, mesh.order);
  Eigen::Matrix3Xd X(3, count);
  for (int q = 0; q < count; ++q) {
    const int e = static_cast<int>(u(rng) * mesh.num_elements()) % mesh.num_elements();
    Eigen::Vector3d xi(u(rng), u(rng), u(rng));
    if (mesh.cell == CellType::Hexahedron) xi = 2.0 * xi - Eigen::Vector3d::Ones();
    else if (xi.sum() > 1.0) xi *= 0.99 / xi.sum();
    const Eigen::VectorXd N = basis.evaluate(xi);
    X.col(q).setZero();
    for (int i = 0; i < basis.size(); ++i) X.col(q) += N[i] * mesh.nodes.col(mesh.elements(i, e));
    element.push_back(e);
  }
  return X;
}

// Isoparametric cells reproduce fields linear in X exactly, values and
// gradients, wherever the inverse map is right: 1e-12 is Newton's round-off.
TEST(StudyPoints, CurvedCellsLocateAndReproduceLinearFields) {
  for (const auto& [cell, order] : {std::pair{CellType::Tetrahedron, 2}, std::pair{CellType::Tetrahedron, 3},
                                    std::pair{CellType::Hexahedron, 2}, std::pair{CellType::Hexahedron, 1}}) {
    const Mesh tube = hollow_cylinder_mesh(0.5, 1.0, 1.0, 2, 8, 2, cell, order);
    std::vector<int> element;
    const Eigen::Matrix3Xd X = points_inside(tube, 300, element);
    const EmbeddedPointMap map = locate_embedded_points(tube, X);
    EXPECT_EQ(map.num_extrapolated, 0) << order;
    Eigen::Matrix3d G;
    G << 0.1, -0.2, 0.3, 0.05, 0.0, 0.4, -0.1, 0.2, 0.0;
    const Eigen::Vector3d c(0.3, -0.1, 0.2);
    Eigen::VectorXd u(3 * tube.num_nodes());
    for (int n = 0; n < tube.num_nodes(); ++n) u.segment<3>(3 * n) = G * tube.nodes.col(n) + c;
    const PointValues v = evaluate_at_points(tube, map, u, true);
    for (int q = 0; q < X.cols(); ++q) {
      ASSERT_LE((v.value.col(q) - G * X.col(q) - c).norm(), 1e-12) << "point " << q;
      ASSERT_LE((v.gradient[q] - G).norm(), 1e-12) << "point " << q;
    }
  }
}

// A point outside every cell goes to a nearby cell and is flagged.
TEST(StudyPoints, PointsOutsideAreExtrapolatedFromANearbyCell) {
  const Mesh tube = hollow_cylinder_mesh(0.5, 1.0, 1.0, 1, 8, 1, CellType::Tetrahedron, 2);
  Eigen::Matrix3Xd X(3, 2);
  X.col(0) << 0.0, 0.0, 0.5;    // on the axis, inside the hole
  X.col(1) << 1.02, 0.0, 0.5;   // just outside the outer surface
  const EmbeddedPointMap map = locate_embedded_points(tube, X);
  EXPECT_EQ(map.num_extrapolated, 2);
  // The cell chosen for the outer point touches the outer surface near it.
  double nearest = 1e300;
  for (int i = 0; i < tube.nodes_per_element(); ++i)
    nearest = std::min(nearest, (tube.nodes.col(tube.elements(i, map.element[1])) - X.col(1)).norm());
  EXPECT_LT(nearest, 0.5);
}

// The lattice surfaces of a unit cube have area 6 exactly (flat faces), for
// every element type; the torus' approaches 4 pi^2 R (r_in + r_out) at the
// isoparametric geometry's rate (relative 1e-3 at these sizes for Tet10).
TEST(StudySurfaces, LatticeAreasAndBodyVolumes) {
  for (const auto& [cell, order] : {std::pair{CellType::Tetrahedron, 1}, std::pair{CellType::Tetrahedron, 2},
                                    std::pair{CellType::Hexahedron, 1}, std::pair{CellType::Hexahedron, 2}}) {
    const Mesh cube = box_mesh(BoxSpec{{0, 0, 0}, {1, 1, 1}, {2, 3, 2}}, cell, order);
    const SurfaceLattice lattice = boundary_lattice(cube, default_subdivisions(cell, order));
    EXPECT_NEAR(deformed_surface(cube, lattice, Eigen::VectorXd::Zero(3 * cube.num_nodes())).area(), 6.0, 1e-12);
    EXPECT_NEAR(body_quadrature(cube, 2 * order).volume(), 1.0, 1e-13);
  }
  const double R = 1.0, a = 0.2, b = 0.5;
  // Both seams merged: (n_r + 1) x n_theta x n_phi vertices, no duplicates.
  EXPECT_EQ(hollow_torus_mesh(R, a, b, 2, 8, 4, CellType::Tetrahedron, 1).num_nodes(), 3 * 8 * 4);
  const Mesh torus = hollow_torus_mesh(R, a, b, 2, 32, 16, CellType::Tetrahedron, 2);
  const SurfaceLattice lattice = boundary_lattice(torus, 4);
  const double area = deformed_surface(torus, lattice, Eigen::VectorXd::Zero(3 * torus.num_nodes())).area();
  EXPECT_NEAR(area / (4 * M_PI * M_PI * R * (a + b)), 1.0, 1e-3);
  EXPECT_NEAR(body_quadrature(torus, 4).volume() / (2 * M_PI * M_PI * R * (b * b - a * a)), 1.0, 1e-3);
}

// Two different meshes carrying the same linear field: no L2 or H1 error;
// translated by d: the RMS and every point's error are d (round-off).
TEST(StudyFieldError, RepresentableFieldsHaveNoErrorAndShiftsMeasureTheShift) {
  const Mesh ref = box_mesh(BoxSpec{{0, 0, 0}, {1, 1, 1}, {3, 3, 3}}, CellType::Tetrahedron, 3);
  const Mesh run = box_mesh(BoxSpec{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}}, CellType::Hexahedron, 2);
  Eigen::Matrix3d G;
  G << 0.1, -0.2, 0.3, 0.05, 0.0, 0.4, -0.1, 0.2, 0.0;
  auto field = [&](const Mesh& m, const Eigen::Vector3d& shift) {
    Eigen::VectorXd u(3 * m.num_nodes());
    for (int n = 0; n < m.num_nodes(); ++n) u.segment<3>(3 * n) = G * m.nodes.col(n) + shift;
    return u;
  };
  const BodyQuadrature q = body_quadrature(ref, 4);
  const PointValues values = q.values(ref, field(ref, Eigen::Vector3d::Zero()));
  const EmbeddedPointMap at = locate_embedded_points(run, q.X);
  const FieldError same = field_error(q, values, run, at, field(run, Eigen::Vector3d::Zero()));
  EXPECT_LE(same.l2, 1e-13);
  EXPECT_LE(same.h1, 1e-13);
  EXPECT_GT(same.reference_h1, 0.1);
  const Eigen::Vector3d shift(0.003, 0.0, -0.004);  // |shift| = 0.005
  const FieldError moved = field_error(q, values, run, at, field(run, shift));
  EXPECT_NEAR(moved.rms(), 0.005, 1e-15);
  EXPECT_NEAR(moved.max_pointwise, 0.005, 1e-15);
  EXPECT_LE(moved.h1, 1e-13);
}

// d / (r^q - 1): errors C h^q at h and h / r differ by C h^q (1 - r^-q), whose
// share of the finer one's error is r^q - 1.
TEST(StudyRichardson, EstimateOfASyntheticSequence) {
  const double C = 2.0, h = 0.1, r = 2.0, q = 3.0;
  const double fine = C * std::pow(h / r, q), coarse = C * std::pow(h, q);
  EXPECT_NEAR(richardson_error(coarse - fine, r, q), fine, 1e-15);
}

struct Scratch {
  fs::path dir = fs::temp_directory_path() / ("hofem_study_" + std::to_string(::getpid()));
  Scratch() { fs::create_directories(dir); }
  ~Scratch() { fs::remove_all(dir); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(dir / name) << text;
    return (dir / name).string();
  }
};

std::string error_of(const std::string& path) {
  try {
    read_study(path);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "no error";
}

// Each malformed study file is refused with the file and the key.
TEST(StudyFile, MalformedStudiesNameTheKey) {
  const Scratch s;
  const std::string scene = std::string(HOFEM_TEST_DATA_DIR) + "/scene_tiny.json";
  const std::string head = R"({"name": "t", "scene": ")" + scene + R"(", )";
  const std::string runs = R"("runs": [{"name": "a", "family": "A"}])";
  const std::string ref = R"("reference": {"overrides": ["mesh.order=2"]}, )";
  struct Case {
    std::string body, expected;
  };
  const std::vector<Case> cases{
      {R"("frames": [0.1], "thresholds": [0.1], )" + ref + R"("runs": [])", "t.json: runs must be a non-empty array"},
      {R"("frames": [0.1], "thresholds": [0.1], )" + ref +
           R"("runs": [{"name": "a/b", "family": "A"}])",
       "t.json: runs[0].name = 'a/b' must be 1-64 of the characters"},
      {R"("frames": [0.1], "thresholds": [0.1], )" + ref +
           R"("runs": [{"name": "a", "family": "A"}, {"name": "a", "family": "B"}])",
       "t.json: runs[1].name = 'a' is used twice"},
      {R"("frames": [0.1], "thresholds": [0.1], )" + ref + R"("runs": [{"name": "a"}])",
       "t.json: key 'runs[0].family' is missing"},
      {R"("frames": [0.1], "thresholds": [0.1], )" + ref +
           R"("runs": [{"name": "a", "family": "A", "overrides": ["material.poisson=0.5"]}])",
       "t.json: runs[0].overrides gives a scene that is not valid: " + scene +
           ": material.poisson = 0.5 is out of range (-1, 0.5)"},
      {R"("frames": [0.2], "thresholds": [0.1], )" + ref + runs, "t.json: frames[0] = 0.2 is out of range (0, 0.1"},
      {R"("frames": [0.1, 0.05], "thresholds": [0.1], )" + ref + runs,
       "t.json: frames[1] must be larger than the value before it"},
      {R"("frames": [0.1], "thresholds": [0], )" + ref + runs, "t.json: thresholds[0] = 0 is out of range (0, "},
      {R"("frames": [0.1], "thresholds": [0.1], "metric": "hausdorff", )" + ref + runs,
       "t.json: metric = 'hausdorff' is not one of: surface_rms, displacement_rms"},
      {R"("frames": [0.1], "thresholds": [0.1], "reference": {"overrides": ["mesh.order=2"], "coarser": "x"}, )" + runs,
       "t.json: reference.coarser must be an array of strings"},
      {R"("frames": [0.1], "thresholds": [0.1], )" + ref +
           R"("runs": [{"name": "a", "family": "A", "overrides": ["integrator=static", "dt=0.1"]}])",
       "gives a scene that is not valid"},
  };
  for (const Case& c : cases) {
    const std::string e = error_of(s.write("t.json", head + c.body + "}"));
    EXPECT_NE(e.find(c.expected), std::string::npos) << "expected: " << c.expected << "\n     got: " << e;
  }
  // A static scene is measured at its solution: frames are refused.
  const std::string st = error_of(s.write(
      "t.json", head + R"("overrides": ["integrator=static", "floor=null"], "frames": [0.1], "thresholds": [0.1], )" +
                    ref + runs + "}"));
  EXPECT_NE(st.find("does not apply to a static scene"), std::string::npos) << st;
}

// The built-in studies, main-job and full size, are valid (every run's scene too).
TEST(StudyFile, BuiltInStudiesAreValid) {
  int count = 0;
  for (const char* sub : {"scripts/studies", "scripts/studies/full"})
    for (const auto& entry : fs::directory_iterator(fs::path(HOFEM_SOURCE_DIR) / sub)) {
      if (entry.path().extension() != ".json") continue;
      EXPECT_NO_THROW(read_study(entry.path().string())) << entry.path();
      ++count;
    }
  EXPECT_GE(count, 4);
}

// End to end on the tiny scene: the runs' rows, errors that fall with
// refinement, the cheapest run under each threshold, and the files.
TEST(StudyRun, TinyStudyWritesItsTable) {
  const Scratch s;
  const Study study = read_study(std::string(HOFEM_TEST_DATA_DIR) + "/study_tiny.json");
  const nlohmann::json j = run_study(study, s.dir.string());
  ASSERT_EQ(j["runs"].size(), 3u);
  for (const auto& r : j["runs"]) {
    ASSERT_TRUE(r["ok"].get<bool>()) << r["message"];
    EXPECT_EQ(r["frames"].size(), 2u);
    EXPECT_GT(r["metric"].get<double>(), 0.0);
    EXPECT_LE(r["floor"]["surface_rms"].get<double>(), 1e-12);  // a box: the lattice is exact at t = 0
  }
  // P1 on 3^3 cells is closer to the P2 reference than P1 on 2^3; P2 on 2^3 closer still.
  const auto metric = [&](int i) { return j["runs"][i]["max_over_frames"]["displacement_rms"].get<double>(); };
  EXPECT_LT(metric(1), metric(0));
  EXPECT_LT(metric(2), metric(1));
  EXPECT_TRUE(j["reference"].contains("richardson"));
  EXPECT_EQ(j["runs"][0]["reference_error"], j["reference"]["richardson"]["estimate"]);  // quoted beside each run
  EXPECT_EQ(j["cheapest"].size(), 2u);
  EXPECT_TRUE(fs::exists(s.dir / "study.json"));
  EXPECT_TRUE(fs::exists(s.dir / "summary.md"));
  EXPECT_TRUE(fs::exists(s.dir / "runs" / "p1-3" / "stats.json"));
  // p2-2 is the coarser reference's discretisation: its row is that run's, not a second run.
  EXPECT_EQ(j["runs"][2]["same_as"], study.coarser_reference->name);
  EXPECT_FALSE(fs::exists(s.dir / "runs" / "p2-2"));
  EXPECT_EQ(j["runs"][2]["max_over_frames"], j["reference"]["richardson"]["distance_to_coarser"]);
  EXPECT_TRUE(j["complete"].get<bool>());
}

// The extended tier: a run marked "extended" is left out unless asked for (listed
// in "left_out", not "pending": the study is complete without it); asked for, it
// runs; once measured and stored it is reported by a study not asking for it.
TEST(StudyRun, ExtendedRunsRunOnlyWhenAskedFor) {
  const Scratch s;
  Study study = read_study(std::string(HOFEM_TEST_DATA_DIR) + "/study_tiny.json");
  study.runs[1].extended = true;  // p1-3
  const nlohmann::json without = run_study(study, s.dir.string(), {.resume = true});
  ASSERT_EQ(without["runs"].size(), 2u);
  EXPECT_EQ(without["left_out"], nlohmann::json::array({"p1-3"}));
  EXPECT_TRUE(without["complete"].get<bool>());
  EXPECT_TRUE(without["pending"].empty());
  EXPECT_FALSE(fs::exists(s.dir / "runs" / "p1-3" / "record.json"));
  std::ifstream summary(s.dir / "summary.md");
  const std::string summary_text((std::istreambuf_iterator<char>(summary)), std::istreambuf_iterator<char>());
  EXPECT_NE(summary_text.find("Left out"), std::string::npos);

  const nlohmann::json with = run_study(study, s.dir.string(), {.resume = true, .extended = true});
  ASSERT_EQ(with["runs"].size(), 3u);
  EXPECT_EQ(with["runs"][1]["name"], "p1-3");
  EXPECT_TRUE(with["runs"][1]["extended"].get<bool>());
  EXPECT_FALSE(with["runs"][1]["stored"].get<bool>());
  EXPECT_TRUE(with["left_out"].empty());

  const nlohmann::json again = run_study(study, s.dir.string(), {.resume = true});
  ASSERT_EQ(again["runs"].size(), 3u);
  EXPECT_TRUE(again["runs"][1]["stored"].get<bool>());
  EXPECT_EQ(again["runs"][1]["max_over_frames"], with["runs"][1]["max_over_frames"]);
  EXPECT_TRUE(again["left_out"].empty());
}

// A resumable run that checkpoints (here after every step; a study's runs every
// 120 s of stepping) writes its recorded states into the checkpoint directory
// before the checkpoint itself, ends with its record and the checkpoint gone,
// and is returned stored, bitwise, when asked again. The first full-size study
// failed at its first checkpoint: "cannot create .../checkpoint/recorded-0-0.state".
TEST(StudyRun, CheckpointedRunRecordsItsStates) {
  const Scratch s;
  const Study study = read_study(std::string(HOFEM_TEST_DATA_DIR) + "/study_tiny.json");
  ASSERT_FALSE(study.runs.front().scene.is_static);
  const std::string dir = (s.dir / "run").string();
  const RecordedRun a = record_run(study.runs.front().scene, dir, study.frames, true, 1);
  ASSERT_TRUE(a.ok) << a.message;
  EXPECT_FALSE(a.stored);
  EXPECT_TRUE(fs::exists(fs::path(dir) / "record.json"));
  EXPECT_FALSE(fs::exists(fs::path(dir) / "checkpoint"));
  const RecordedRun b = record_run(study.runs.front().scene, dir, study.frames, true, 1);
  EXPECT_TRUE(b.stored);
  ASSERT_EQ(b.states.size(), a.states.size());
  for (size_t k = 0; k < a.states.size(); ++k) EXPECT_TRUE(b.states[k] == a.states[k]) << k;
}

// A run stopped part-way continues from its checkpoint: the progress callback
// hears the checkpoint's time first (resumed, an earlier session's work) and
// then only the steps after it, and the states equal an unbroken run's.
TEST(StudyRun, ResumedRunReportsWhereItResumed) {
  const Scratch s;
  const Study study = read_study(std::string(HOFEM_TEST_DATA_DIR) + "/study_tiny.json");
  const Scene& scene = study.runs.front().scene;
  ASSERT_FALSE(scene.is_static);
  const double dt = scene.dynamics.dt;
  const int total = static_cast<int>(std::ceil(scene.duration / dt - 1e-9));
  ASSERT_GE(total, 4);
  const RecordedRun unbroken = record_run(scene, (s.dir / "unbroken").string(), study.frames, true, 1);
  ASSERT_TRUE(unbroken.ok) << unbroken.message;
  // Stop at the third step: the checkpoint of step 2 (every step) stays behind.
  const std::string dir = (s.dir / "stopped").string();
  const RecordedRun stopped = record_run(scene, dir, study.frames, true, 1, [&](double t, bool) {
    if (t > 2.5 * dt) throw std::runtime_error("stopped");
  });
  ASSERT_FALSE(stopped.ok);
  ASSERT_TRUE(fs::exists(fs::path(dir) / "checkpoint"));
  std::vector<std::pair<double, bool>> heard;
  const RecordedRun resumed =
      record_run(scene, dir, study.frames, true, 1, [&](double t, bool r) { heard.emplace_back(t, r); });
  ASSERT_TRUE(resumed.ok) << resumed.message;
  ASSERT_EQ(heard.size(), static_cast<size_t>(total - 2 + 1));
  EXPECT_TRUE(heard.front().second);
  EXPECT_NEAR(heard.front().first, 2 * dt, 1e-12);  // t accumulated in two additions of dt
  for (size_t k = 1; k < heard.size(); ++k) EXPECT_FALSE(heard[k].second) << k;
  ASSERT_EQ(resumed.states.size(), unbroken.states.size());
  for (size_t k = 0; k < resumed.states.size(); ++k) EXPECT_TRUE(resumed.states[k] == unbroken.states[k]) << k;
}

// A threshold the instrument cannot resolve stops the study.
TEST(StudyRun, ThresholdBelowTheMeasuringFloorIsRefused) {
  const Scratch s;
  Study study = read_study(std::string(HOFEM_TEST_DATA_DIR) + "/study_tiny.json");
  study.reference.scene = read_scene(study.scene_file, {"mesh.order=2", "mesh.box.cells=[1,1,1]",
                                                        "mesh.box.min=[0,0,0.1]", "mesh.box.max=[1,1,1.1]"});
  study.coarser_reference.reset();
  study.thresholds = {1e-30};
  try {
    run_study(study, s.dir.string());
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("below 10 x the measuring floor"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace hofem
