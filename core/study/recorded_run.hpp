#pragma once
// One scene run as a study measures it: the mesh that carries the displacement,
// for a finite-cell run also its embedded surface, active cells and own
// quadrature, and the displacement at chosen times (t = 0 always: the faceting
// floor), taken from the run through SceneRunOptions::observer - nothing is read
// back from VTU frames, and nothing is recorded between the chosen times.
#include "embedded/element_rules.hpp"
#include "mesh/mesh.hpp"
#include "scene/scene.hpp"

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace hofem {

struct RecordedRun {
  Mesh mesh;                            ///< carries u (a finite-cell run's background)
  std::optional<Mesh> embedded_surface; ///< finite-cell runs: the geometry's boundary triangles
  std::vector<char> active;             ///< finite-cell runs: cells that integrate something (else empty)
  ElementQuadratureList own_rules;      ///< finite-cell runs: each cell's mass rule (null = standard)
  /// The recorded states: times[0] = 0, then one per requested time (the step
  /// nearest to it; a static scene's one state is at t = 1).
  std::vector<double> times;
  std::vector<Eigen::VectorXd> states;
  /// stats.json of the run; an empty object when it failed before the runner wrote any (a mesh refused).
  nlohmann::json stats = nlohmann::json::object();
  bool ok = false;
  std::string message;
  /// Taken from a stored record of an earlier run of the same scene (resumable).
  bool stored = false;
};

/// A run's progress: the time reached, and whether it was reached by resuming.
using StepCallback = std::function<void(double t, bool resumed)>;

/// Runs the scene without frames into `out_dir` (stats.json only; empty: no
/// files) and records
/// its state at t = 0 and at each time in `frame_times` (ascending; at most the
/// scene's duration; a static scene's solution is at t = 1). A run that fails is returned with ok = false, its message
/// and what it recorded.
RecordedRun record_run(const Scene& scene, const std::string& out_dir, const std::vector<double>& frame_times,
                       bool resumable = false, int checkpoint_every_steps = 0,
                       const StepCallback& on_step = {});
// resumable (needs out_dir): the finished run's record is stored in out_dir
// (record.json and a state file per recorded time, keyed by the scene's
// fingerprint and the times) and returned again without running when asked for
// the same scene and times; a run that stops part-way continues from its last
// on_step: called with the time after every step (resumed = false), and once
// with the checkpoint's time when the run continues from one (resumed = true:
// the steps before it are not this session's work; a study's ETA leaves them out).
// checkpoint (out_dir/checkpoint, every 120 s of stepping, and every
// checkpoint_every_steps steps when > 0: tests) with what it had
// recorded. Stored results do not know which code made them beyond their
// provenance: a study asked to resume after a change of the code reuses them
// (the study's rows say which runs were stored).

/// A finite-cell run taken from its record (stored) has its surface and active
/// cells but not its rules; a reference needs its cells' mass rules to integrate
/// over the geometry (ReferenceMeasure): this builds them (SceneEmbedding). No-op
/// for other runs and for runs that have them.
void add_own_rules(RecordedRun& run, const Scene& scene);

/// What a run's record is keyed by: its scene's fingerprint (scene_fingerprint.hpp)
/// and the recorded times.
std::string record_key(const Scene& scene, const std::vector<double>& frame_times);

/// A finished run's errors as a study measured them against a reference, kept in
/// its record (record.json "measured", keyed by the measurement: the reference's
/// record key and how it measures), so that a study run in parts need not keep
/// the states of every run: at the seeds' sizes they are 10 MB each, and only
/// the reference's are needed to measure a run not yet measured.
struct StoredMeasure {
  nlohmann::json stats;   ///< the run's stats.json
  nlohmann::json errors;  ///< what the study measured (its row's error fields)
};
/// The stored measurement of the run of `scene` in `dir` when its record is of
/// the same scene and times and was measured under `measure_key`; else nothing.
std::optional<StoredMeasure> stored_measure(const Scene& scene, const std::string& dir,
                                            const std::vector<double>& frame_times, const std::string& measure_key);
/// Adds the measurement to the finished run's record in `dir` (atomically), then
/// removes the record's state files when `drop_states`: the record then stays
/// good for its measurement only, and a study under another reference runs it
/// again.
void store_measure(const std::string& dir, const std::string& measure_key, const nlohmann::json& errors,
                   bool drop_states);

}  // namespace hofem
