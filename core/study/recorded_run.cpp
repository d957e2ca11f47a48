#include "study/recorded_run.hpp"

#include "scene/scene_embedding.hpp"
#include "scene/scene_runner.hpp"

#include "io/atomic_file.hpp"
#include "scene/scene_fingerprint.hpp"
#include "scene/scene_mesh.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace hofem {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Long study runs checkpoint this often (a few seconds of writing per hour).
constexpr double kCheckpointSeconds = 120.0;

// The recorded states as state files in dir (x: the displacement; v: unused, zero),
// named by time index and step so that a file once written never changes.
json write_recorded(const std::string& dir, const RecordedRun& run, const std::vector<int>& steps) {
  json files = json::array();
  for (size_t f = 0; f < run.states.size(); ++f) {
    if (run.states[f].size() == 0) {
      files.push_back(nullptr);
      continue;
    }
    const std::string name = fmt::format("recorded-{}-{}.state", f, steps[f]);
    if (!fs::exists(fs::path(dir) / name))
      write_state((fs::path(dir) / name).string(),
                  StoredState{"recorded", run.times[f], steps[f], run.states[f], Eigen::VectorXd::Zero(run.states[f].size())});
    files.push_back({{"file", name}, {"t", run.times[f]}, {"step", steps[f]}});
  }
  return files;
}

void read_recorded(const std::string& dir, const json& files, RecordedRun& run, std::vector<int>& steps, int up_to_step) {
  for (size_t f = 0; f < files.size() && f < run.states.size(); ++f) {
    if (files[f].is_null() || files[f]["step"].get<int>() > up_to_step) continue;
    const StoredState s = read_state((fs::path(dir) / files[f]["file"].get<std::string>()).string());
    run.times[f] = s.t;
    run.states[f] = s.x;
    steps[f] = s.step;
  }
}

// record.json in dir when it is a record of `key`; else a discarded value.
json read_record(const std::string& dir, const std::string& key) {
  std::ifstream in(fs::path(dir) / "record.json");
  if (!in) return json(json::value_t::discarded);
  std::stringstream text;
  text << in.rdbuf();
  json j = json::parse(text.str(), nullptr, false);
  if (j.is_discarded() || !j.is_object() || j.value("key", "") != key || !j.contains("files") ||
      !j.contains("stats"))
    return json(json::value_t::discarded);
  return j;
}

// A stored finished run: its states, and the mesh and embedding built again from
// the scene. Nothing when a state file is gone (store_measure dropped it).
std::optional<RecordedRun> stored_run(const Scene& scene, const std::string& dir, const std::string& key, size_t n) {
  const json j = read_record(dir, key);
  if (j.is_discarded()) return std::nullopt;
  for (const json& f : j.at("files"))
    if (!f.is_null() && !fs::exists(fs::path(dir) / f.at("file").get<std::string>())) return std::nullopt;
  RecordedRun run;
  run.times.assign(n, std::numeric_limits<double>::quiet_NaN());
  run.states.resize(n);
  std::vector<int> steps(n, 0);
  read_recorded(dir, j.at("files"), run, steps, std::numeric_limits<int>::max());
  run.mesh = build_scene_mesh(scene);
  if (scene.embedded) {
    // The surface and active cells only: the rules are not needed to measure a
    // run, and an unsimplified run's would not fit (embedded_geometry). A stored
    // reference gets its mass rules from add_own_rules.
    EmbeddedGeometry g = embedded_geometry(scene, run.mesh);
    run.embedded_surface = std::move(g.surface);
    run.active = std::move(g.active);
  }
  run.stats = j.at("stats");
  run.ok = j.at("ok").get<bool>();
  run.message = j.at("message").get<std::string>();
  run.stored = true;
  return run;
}

}  // namespace

void add_own_rules(RecordedRun& run, const Scene& scene) {
  if (!scene.embedded || !run.own_rules.empty()) return;
  const SceneEmbedding emb(scene, run.mesh);
  run.own_rules = emb.element_rules().mass;
}

std::string record_key(const Scene& scene, const std::vector<double>& frame_times) {
  return scene_fingerprint(scene) + ":" + json(frame_times).dump();
}

std::optional<StoredMeasure> stored_measure(const Scene& scene, const std::string& dir,
                                            const std::vector<double>& frame_times, const std::string& measure_key) {
  const json j = read_record(dir, record_key(scene, frame_times));
  if (j.is_discarded() || !j.value("ok", false) || !j.contains("measured") ||
      j["measured"].value("key", "") != measure_key)
    return std::nullopt;
  return StoredMeasure{j.at("stats"), j["measured"].at("errors")};
}

void store_measure(const std::string& dir, const std::string& measure_key, const json& errors, bool drop_states) {
  const fs::path path = fs::path(dir) / "record.json";
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  json j = json::parse(text.str(), nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("files"))
    throw std::runtime_error(fmt::format("{}: not a run's record: cannot store its measurement", path.string()));
  j["measured"] = {{"key", measure_key}, {"errors", errors}};
  write_file_atomically(path.string(), j.dump() + "\n");
  if (!drop_states) return;
  std::error_code ec;
  for (const json& f : j.at("files"))
    if (!f.is_null()) fs::remove(fs::path(dir) / f.at("file").get<std::string>(), ec);
}

RecordedRun record_run(const Scene& scene, const std::string& out_dir, const std::vector<double>& frame_times,
                       bool resumable, int checkpoint_every_steps, const StepCallback& on_step) {
  const std::string key = resumable && !out_dir.empty() ? record_key(scene, frame_times) : std::string();
  if (!key.empty())
    if (std::optional<RecordedRun> stored = stored_run(scene, out_dir, key, 1 + frame_times.size())) return *stored;
  RecordedRun run;
  std::vector<int> steps(1 + frame_times.size(), 0);
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
    if (on_step) on_step(s.t, false);
    for (size_t f = 0; f < frame_times.size(); ++f) {
      if (std::abs(s.t - frame_times[f]) < gap[f]) {
        gap[f] = std::abs(s.t - frame_times[f]);
        run.times[f + 1] = s.t;
        run.states[f + 1] = s.u;
        steps[f + 1] = s.step;
      }
    }
  };
  // Static scenes have no steps to checkpoint; they are stored when finished.
  if (!key.empty() && !scene.is_static) {
    options.checkpoint_dir = (fs::path(out_dir) / "checkpoint").string();
    options.checkpoint_every_seconds = kCheckpointSeconds;
    options.checkpoint_every_steps = checkpoint_every_steps;
    options.resume = true;
    options.checkpoint_record = [&](const std::string& dir, int) { return write_recorded(dir, run, steps); };
    options.on_resume = [&](const json& files, int step, double t) {
      if (on_step) on_step(t, true);
      if (!files.is_array()) return;
      read_recorded(options.checkpoint_dir, files, run, steps, step);
      for (size_t f = 0; f < frame_times.size(); ++f)
        if (run.states[f + 1].size() > 0) gap[f] = std::abs(run.times[f + 1] - frame_times[f]);
    };
  }
  try {
    const SceneRunResult r = run_scene(scene, out_dir, options);
    run.ok = r.ok;
    run.message = r.message;
    run.stats = r.stats;
  } catch (const std::exception& e) {
    run.ok = false;
    run.message = e.what();
  }
  if (!key.empty() && run.ok) {
    // The finished run's record: its states first, then record.json naming them.
    const json files = write_recorded(out_dir, run, steps);
    write_file_atomically((fs::path(out_dir) / "record.json").string(),
                          json{{"key", key}, {"files", files}, {"stats", run.stats}, {"ok", run.ok}, {"message", run.message}}
                                  .dump() +
                              "\n");
    std::error_code ec;
    fs::remove_all(fs::path(out_dir) / "checkpoint", ec);
  }
  return run;
}

}  // namespace hofem
