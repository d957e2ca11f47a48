#pragma once
// Runs a scene: builds the mesh, material and boundary motions, steps the
// dynamics (or solves the static problem) and writes into an output directory
//   frame_00000.vtu ...  displacement and velocity per node, strain-energy
//                        density per cell (a frame every output.every steps)
//   <name>.pvd           the frames with their times (ParaView opens this)
//   stats.json           per step: Newton and linear iterations, residual,
//                        energies, seconds; at the end: totals and what was
//                        built and how often (DynamicsStats)
// Embedded scenes (scene.hpp) also write
//   frame_00000_surface.vtu ...  the embedded surface (triangles) with its
//                        displacement interpolated from the background
//   <name>_surface.pvd   those frames
// and their frames of the background carry each cell's volume_fraction; stats.json
// gains "embedded" (cells cut / empty / dropped / stabilised, quadrature points
// before and after simplification and their seconds, extrapolated surface
// vertices: scene_embedding.hpp), and the per-step mean_displacement and lowest_z
// are taken over the embedded surface's vertices instead of the mesh nodes.
// With SceneRunOptions::final_frame and no frames: final.vtu (and
// final_surface.vtu), the last state only.
#include "io/state_file.hpp"
#include "io/vtu_writer.hpp"
#include "scene/scene.hpp"

#include <nlohmann/json.hpp>

#include <functional>
#include <string>

namespace hofem {

class SceneEmbedding;

/// A scene's state handed to SceneRunOptions::observer: the mesh that carries
/// the displacement (the background of an embedded scene), the embedding, the
/// time and the whole body's displacement (3 per node).
struct SceneState {
  const Mesh& mesh;
  const SceneEmbedding* embedding;  ///< null unless the scene is embedded
  int step;                         ///< 0: the initial state
  double t;                         ///< static scenes: 0, then 1 (the end of the load path)
  const Eigen::VectorXd& u;
};

struct SceneRunOptions {
  bool progress = false;  ///< a progress bar on stderr
  bool write_frames = true;
  /// With write_frames false: still write the last state as final.vtu (and
  /// final_surface.vtu when embedded), not listed in a .pvd - a picture of the
  /// result without every frame's cost (hofem run --final-frame).
  bool final_frame = false;
  /// Encoding of the .vtu files (the CLI's --vtu-format; ASCII here, which tests read as text).
  VtuFormat vtu_format = VtuFormat::ascii;
  /// Over the MPI ranks (static scenes and implicit Euler): every rank
  /// runs the scene on its part of the elements, rank 0 writes the frames and
  /// stats.json (the state is replicated, so they are the whole body's).
  bool distributed = false;
  /// When set: called on the writing rank with the initial state and after every
  /// step that succeeded (a static scene: after the solve). Studies (study/)
  /// measure errors from it; it does not count in the steps' seconds.
  std::function<void(const SceneState&)> observer;
  /// Time-stepping scenes, serial: continue from this stored state (its time
  /// and step; the scene's duration stays the end time) instead of from rest.
  /// Its size must be the mesh's; the caller checks its key.
  const StoredState* start = nullptr;
  /// Time-stepping scenes, serial: write the last state reached here (a
  /// state file, io/state_file.hpp) under this key.
  std::string save_state;
  std::string save_state_key;
  /// Time-stepping scenes, serial: a checkpoint (scene/run_checkpoint.hpp) in
  /// this directory after every checkpoint_every_steps-th step and whenever
  /// checkpoint_every_seconds of stepping passed since the last one (either 0:
  /// that trigger off); empty: no checkpoints.
  std::string checkpoint_dir;
  int checkpoint_every_steps = 0;
  double checkpoint_every_seconds = 0.0;
  /// Continue from checkpoint_dir's checkpoint when there is one (it must be of
  /// this scene): the earlier frames and per-step rows stay, the steps after it
  /// are run. Without a checkpoint the run starts from rest.
  bool resume = false;
  /// With checkpoints: called before each is committed, with its directory and
  /// step; what it returns is kept in the checkpoint and handed to on_resume
  /// when a run continues from it (a study's recorded states), with the
  /// checkpoint's step and time.
  std::function<nlohmann::json(const std::string& dir, int step)> checkpoint_record;
  std::function<void(const nlohmann::json& record, int step, double t)> on_resume;
};

struct SceneRunResult {
  bool ok = true;
  std::string message;
  nlohmann::json stats;  ///< what stats.json holds
};

/// An empty out_dir writes nothing (write_frames must then be false): the
/// result's stats are all there is. Throws SceneError for problems found before stepping (mesh, node sets,
/// output directory); a failed step ends the run with ok = false and the
/// message, after writing what was computed.
SceneRunResult run_scene(const Scene& scene, const std::string& out_dir, const SceneRunOptions& options = {});

}  // namespace hofem
