// The instrument of hofem study (core/study) checked where the answer is known,
// on real scene runs:
//  1. a run against itself: surface distance and displacement error 0;
//  2. the run translated rigidly by d: the displacement error is d at every
//     point (RMS = max = d), and the surface distance's max is d (the shift moves
//     every point by d; a translation tangent to a face moves it within its own
//     plane, so the surface RMS is below d);
//  3. a refinement sequence: Tet10 at three sizes against a Tet20 reference of a
//     smooth static scene, the L2 error's rate in [p + 0.7, p + 1.3] (asymptotically
//     p + 1 = 3).
// 1 and 2 use a clamped cube under its own weight. 3 needs a solution without
// singularities: a box or a tube has 90-degree edges where clamped faces meet
// (the Lame system's corner exponent there is ~1.4 for nu = 0.3, which caps the
// L2 rate near 2.8 and approaches it slowly: measured 2.44, 2.50, 2.53, 2.58
// for the clamped cube at 4, 5, 6, 8 cells against Tet20 at 10), so the scene
// is a hollow torus - no edges - held on its inner surface, free outside,
// under its own weight (measured 2.81, then 3.16-3.25).
#include "study_checks.hpp"

#include "study/scene_error.hpp"

#include <fmt/format.h>

#include <cmath>
#include <string>
#include <vector>

namespace hofem::verification {

namespace {

constexpr const char* kCube = R"({
  "name": "clamped-cube-under-gravity",
  "mesh": {"box": {"min": [0, 0, 0], "max": [1, 1, 1], "cells": [3, 3, 3]}, "cell": "tet", "order": 2},
  "material": {"model": "stable-neohookean", "young": 1e5, "poisson": 0.3, "density": 1000},
  "integrator": "static",
  "gravity": [0, 0, -9.81],
  "boundary": [{"nodes": "boundary", "motion": "fixed"}]
})";

// Linear elasticity: one Newton step per solve; the solution's smoothness, not
// the material, is what the rate depends on.
constexpr const char* kTorus = R"({
  "name": "torus-held-inside-under-gravity",
  "mesh": {"torus": {"major_radius": 1.0, "r_in": 0.2, "r_out": 0.5, "cells": [1, 8, 4]}, "cell": "tet", "order": 2},
  "material": {"model": "linear", "young": 1e5, "poisson": 0.3, "density": 1000},
  "integrator": "static",
  "gravity": [0, 0, -9.81],
  "boundary": [{"nodes": "inner", "motion": "fixed"}]
})";

// Every run records t = 0 and one requested time (the static solution at t = 1).
constexpr int kRequestedStates = 2;

// States a run recorded (RecordedRun::times is NaN where none was): a static
// scene records its solution only when Newton converged (scene_runner.cpp), so
// the count is the run's convergence, measured, not a flag.
int recorded_states(const RecordedRun& run) {
  int n = 0;
  for (size_t i = 0; i < run.times.size(); ++i) n += std::isfinite(run.times[i]) && run.states[i].size() > 0;
  return n;
}

// "converged": the states recorded against the states requested.
bool check_recorded(Report& report, const std::string& group, const std::string& name, const RecordedRun& run) {
  const int recorded = recorded_states(run);
  report.check(group, name, recorded, kRequestedStates, Compare::AtLeast,
               fmt::format("states recorded of the {} requested (t = 0 and the static solution, recorded only when "
                           "Newton converged): {}",
                           kRequestedStates, run.message.empty() ? "no message" : run.message));
  return run.ok && recorded == kRequestedStates;
}

RecordedRun torus(int k, int order) {
  const Scene s = parse_scene(kTorus, "study_checks.cpp: torus",
                              {fmt::format("mesh.torus.cells=[{},{},{}]", k, 8 * k, 4 * k), fmt::format("mesh.order={}", order)});
  return record_run(s, "", {1.0});
}

void add_identity_checks(Report& report, const std::string& group) {
  const RecordedRun cube = record_run(parse_scene(kCube, "study_checks.cpp: clamped cube"), "", {1.0});
  if (!check_recorded(report, group, "clamped cube converged", cube)) return;
  const ReferenceMeasure measure(cube, 0);
  const double sag = cube.states[1].cwiseAbs().maxCoeff();
  report.measure(group, "clamped cube max displacement", sag, "the sag under its weight");

  // 1. Against itself: every located point is the run's own (round-off in the
  // inverse map, 1e-13 of the size, moves it by ~1e-13 of the field).
  const StateError self = scene_error(cube, measure, 0).back();
  report.check(group, "run against itself: surface RMS / sag", self.surface.rms() / sag, 1e-12, Compare::AtMost,
               "identical surfaces: 0 up to round-off");
  report.check(group, "run against itself: surface max / sag", self.surface.max() / sag, 1e-12, Compare::AtMost,
               "identical surfaces: 0 up to round-off");
  report.check(group, "run against itself: displacement RMS / sag", self.field.rms() / sag, 1e-12, Compare::AtMost,
               "the same field at the same points: 0 up to round-off");

  // 2. Translated by d = 0.01 along (1, 2, 2) / 3: u + d at every node
  // reproduces u + d at every point (constants are in every Lagrange space).
  const double d = 0.01;
  const Eigen::Vector3d shift = d * Eigen::Vector3d(1, 2, 2) / 3.0;
  RecordedRun moved = cube;
  for (Eigen::VectorXd& u : moved.states) u += shift.replicate(u.size() / 3, 1);
  const StateError t = scene_error(moved, measure, 0).back();
  report.check(group, "translated by d: |displacement RMS / d - 1|", std::abs(t.field.rms() / d - 1), 1e-12,
               Compare::AtMost,
               "u_run - u_ref = the shift at every point: the sums of ~10^4 weights round at ~1e-14 relative");
  report.check(group, "translated by d: |max pointwise / d - 1|", std::abs(t.field.max_pointwise / d - 1), 1e-12,
               Compare::AtMost, "the shift at every point: round-off");
  report.check(group, "translated by d: |surface max / d - 1|", std::abs(t.surface.max() / d - 1), 1e-9,
               Compare::AtMost,
               "every point moves by d, so none is further than d from the original surface; the corner (1, 1, 1), "
               "pushed outward along the shift, is exactly d from it and is a sampled vertex (1e-9: round-off)");
  report.check(group, "translated by d: surface RMS / d", t.surface.rms() / d, 1.0 + 1e-9, Compare::AtMost,
               "no point moves further than d");
}

}  // namespace

void add_study_checks(Report& report) {
  const std::string group = "study";
  add_identity_checks(report, group);

  // 3. Tet10 at k = 1, 2, 3 (cells k x 8k x 4k) against Tet20 at k = 4.
  const RecordedRun reference = torus(4, 3);
  if (!check_recorded(report, group, "torus Tet20 reference converged", reference)) return;
  const ReferenceMeasure measure(reference, 0);
  std::vector<double> h, e;
  for (const int k : {1, 2, 3}) {
    const RecordedRun run = torus(k, 2);
    if (!check_recorded(report, group, fmt::format("torus Tet10 k = {} converged", k), run)) return;
    const StateError err = scene_error(run, measure, 0).back();
    h.push_back(1.0 / k);
    e.push_back(err.field.l2);
    report.measure(group, fmt::format("torus Tet10 k = {}: L2 error / reference L2 norm", k),
                   err.field.l2 / err.field.reference_l2, "relative displacement error against Tet20 k = 4");
  }
  // Least-squares slope of log e against log h over the three sizes.
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = 0; i < h.size(); ++i) {
    const double x = std::log(h[i]), y = std::log(e[i]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  const double n = static_cast<double>(h.size());
  const double rate = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  // Above: 3 + 0.3. The slope measures 2.93 (pairs 2.81 and 3.18; finer sizes
  // gave 3.16-3.25, pre-asymptotic from above), so 3.3 holds even for the finest
  // pair alone; a whole order faster (4, the reference's own rate) fails.
  report.check_rate(group, "torus Tet10 refinement: L2 rate against the Tet20 reference", rate, 3.0, 0.3, 0.3,
                    "asymptotically p + 1 = 3 for a smooth solution; p + 0.7 leaves room for the coarsest size "
                    "(k = 1: one cell through the wall) and the reference's own error (O(h^4), ~1/10 of the finest)");
}

}  // namespace hofem::verification
