#include "study/recorded_run.hpp"

#include "scene/scene_embedding.hpp"
#include "scene/scene_runner.hpp"

#include <cmath>
#include <limits>

namespace hofem {

RecordedRun record_run(const Scene& scene, const std::string& out_dir, const std::vector<double>& frame_times) {
  RecordedRun run;
  // Per requested time: the recorded state's distance in time (the nearest step wins).
  std::vector<double> gap(frame_times.size(), std::numeric_limits<double>::infinity());
  run.times.assign(1 + frame_times.size(), std::numeric_limits<double>::quiet_NaN());
  run.states.resize(1 + frame_times.size());
  SceneRunOptions options;
  options.write_frames = false;
  options.observer = [&](const SceneState& s) {
    if (s.step == 0) {
      run.mesh = s.mesh;
      if (s.embedding) {
        run.embedded_surface = s.embedding->surface();
        run.active = s.embedding->active_cells();
        run.own_rules = s.embedding->element_rules().mass;
      }
      run.times[0] = s.t;
      run.states[0] = s.u;
      return;
    }
    for (size_t f = 0; f < frame_times.size(); ++f) {
      if (std::abs(s.t - frame_times[f]) < gap[f]) {
        gap[f] = std::abs(s.t - frame_times[f]);
        run.times[f + 1] = s.t;
        run.states[f + 1] = s.u;
      }
    }
  };
  try {
    const SceneRunResult r = run_scene(scene, out_dir, options);
    run.ok = r.ok;
    run.message = r.message;
    run.stats = r.stats;
  } catch (const std::exception& e) {
    run.ok = false;
    run.message = e.what();
  }
  return run;
}

}  // namespace hofem
