#pragma once
// A study: one scene, a reference discretisation and a list of others, each
// given as overrides of the scene's keys (scene.hpp: SceneOverrides - the one
// override mechanism, so every discretisation is validated exactly like a scene
// file). hofem study runs them all and sets run time against error (study.hpp).
// JSON Schema: study.schema.json beside this file (SCENE_FORMAT.md documents it).
//
// {
//   "$schema": "../../core/study/study.schema.json",   (optional: for editors; ignored)
//   "name": "twisting-cylinder",                        (the output folder's name)
//   "scene": "../scenes/twisting-cylinder-p2.json",     (relative to the study file)
//   "overrides": ["duration=0.5"],                      (every run and the reference; optional)
//   "frames": [0.25, 0.5],     (times at which errors are measured; dynamic scenes only;
//                               a static scene is measured at its one solution)
//   "metric": "surface_rms",   (or "displacement_rms": what the thresholds bound; optional)
//   "thresholds": [0.02, 0.01],  (the cheapest run with metric <= each is reported)
//   "subdivisions": 4,         (pieces per face edge for the surface distance; optional,
//                               default 1 for Tet4, 2 p otherwise)
//   "reference": {"name": "tet10-fine", "overrides": [...],
//                 "coarser": [...]},   (optional: a coarser reference level, overrides
//                                       replacing the reference's, for the Richardson
//                                       estimate of the reference's own error)
//   "runs": [{"name": "tet4-a", "family": "Tet4 FEM", "overrides": ["mesh.order=1"]}, ...]
//            ("extended": true on a run: run only by `hofem study --extended`, for the
//             costliest rungs of a ladder that a time-budgeted job leaves out)
// }
#include "scene/scene.hpp"

#include <optional>
#include <string>
#include <vector>

namespace hofem {

struct StudyRun {
  std::string name;        ///< [A-Za-z0-9._-]+, unique in the study (its folder under runs/)
  std::string family;      ///< the plot's marker ("Tet10 FEM")
  SceneOverrides overrides;
  Scene scene;             ///< the scene with the study's and the run's overrides, validated
  /// Run only when asked (StudyRunOptions::extended); otherwise a stored
  /// measurement of it is still reported, and without one it is listed as left out.
  bool extended = false;
};

struct Study {
  std::string file;        ///< where it was read from (messages)
  std::string name;
  std::string scene_file;  ///< resolved against the study file's folder
  SceneOverrides overrides;
  std::vector<double> frames;
  std::string metric = "surface_rms";
  std::vector<double> thresholds;
  int subdivisions = 0;    ///< 0: default_subdivisions
  StudyRun reference;
  std::optional<StudyRun> coarser_reference;
  std::vector<StudyRun> runs;
};

/// Reads and validates a study file and every discretisation's scene; throws
/// SceneError naming the file and key (a run's scene error names the run too).
Study read_study(const std::string& path);
/// The same for JSON text; `origin` names it and relative paths start from its folder.
Study parse_study(const std::string& text, const std::string& origin);

}  // namespace hofem
