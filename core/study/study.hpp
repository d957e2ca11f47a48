#pragma once
// Runs a study (study_file.hpp) and sets each discretisation's cost against its
// error on the scene, the question of both Longva et al. 2020 §6.2 ("which
// discretisation reaches a given accuracy fastest?") and the thesis' element
// order comparisons. Into the output folder:
//   study.json   per run: unknowns, elements, quadrature points, time per step
//                (median), total time, Newton and linear iterations, the errors
//                at each frame and their max over frames, the faceting floor
//                (t = 0); the reference's own error estimate (Richardson, from
//                the coarser reference level) beside every run's errors; per threshold the
//                cheapest run overall and per family
//   summary.md   the same as a table
//   runs/NAME/stats.json   each run's own statistics (scene_runner.hpp)
// The measuring floor - the surface distance of the reference's undeformed
// surface at the study's subdivisions against twice as many - must be at most
// 10 % of every surface threshold, or the study stops with an error: a
// threshold the instrument cannot resolve would make the verdicts noise.
#include "study/study_file.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace hofem {

struct StudyRunOptions {
  bool progress = false;  ///< one line per run on stderr
  /// Keep each finished run's record under out_dir/runs/NAME and take it
  /// instead of running again when the run's scene is unchanged; a run stopped
  /// part-way continues from its checkpoint (study/recorded_run.hpp).
  bool resume = false;
  /// Run the runs marked "extended" too. Without it they are reported from a
  /// stored measurement (resume) when there is one, else listed as left out.
  bool extended = false;
};

/// Runs the study and writes its files into out_dir; returns study.json's content.
/// Throws SceneError if the reference fails or the thresholds are below the floor.
nlohmann::json run_study(const Study& study, const std::string& out_dir, const StudyRunOptions& options = {});

/// Richardson's estimate of a reference's own error from its distance d to a
/// coarser level: d / (r^q - 1), r the refinement ratio (h_coarse / h_ref) and
/// q the error's asymptotic order. Assumes both levels are in the asymptotic
/// range; the estimate is a size, not a bound.
double richardson_error(double distance_to_coarser, double ratio, double order);

}  // namespace hofem
